// light_pad.js: the published page's light control: the hemisphere towards the camera seen from
// the camera, the captured lights as dots and the light as a ring; dragging moves the light.

export class LightPad {
  constructor(canvas, directions, onMove) {
    this.canvas = canvas;
    this.directions = directions;
    this.onMove = onMove;
    const move = (event) => {
      const box = canvas.getBoundingClientRect();
      let x = ((event.clientX - box.left) / box.width) * 2 - 1;
      let y = 1 - ((event.clientY - box.top) / box.height) * 2;
      const r = Math.hypot(x, y);
      if (r > 1) x /= r, y /= r;
      onMove([x, y, Math.sqrt(Math.max(0, 1 - x * x - y * y))]);
    };
    canvas.addEventListener('pointerdown', (event) => {
      canvas.setPointerCapture(event.pointerId);
      move(event);
    });
    canvas.addEventListener('pointermove', (event) => {
      if (canvas.hasPointerCapture(event.pointerId)) move(event);
    });
  }

  draw(light) {
    const g = this.canvas.getContext('2d'), size = this.canvas.width, r = size / 2 - 6;
    const at = (d) => [size / 2 + d[0] * r, size / 2 - d[1] * r];
    g.clearRect(0, 0, size, size);
    g.fillStyle = '#24272e';
    g.strokeStyle = '#4a505c';
    g.beginPath();
    g.arc(size / 2, size / 2, r, 0, 2 * Math.PI);
    g.fill();
    g.stroke();
    g.fillStyle = '#7d8796';
    for (const d of this.directions)
      if (d[2] >= 0) {
        const [x, y] = at(d);
        g.fillRect(x - 1.5, y - 1.5, 3, 3);
      }
    const n = Math.hypot(...light), [x, y] = at(light.map((v) => v / n));
    g.strokeStyle = '#ffd24a';
    g.lineWidth = 2.5;
    g.beginPath();
    g.arc(x, y, 7, 0, 2 * Math.PI);
    g.stroke();
  }
}
