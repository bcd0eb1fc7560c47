// light_vector.js: the light vector of a light moved between the captured ones, as `relume relight
// --light-dir` makes it, and that vector in the field's basis, as relume's relighters use it.
// Weights: spherical barycentric on the triangulation that `relume publish` wrote (from
// lib/lighting/light_interpolation.cpp's LightInterpolation), the nearest rim point for a
// direction outside it; the arithmetic follows that file step for step, in double precision, and
// rounds to float where relume does (LightRgb and the Haar transform are float there).

const f32 = Math.fround;
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => Math.sqrt(dot(a, a));
const scaled = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
const unit = (a) => scaled(a, 1 / norm(a));
const angleBetween = (a, b) => Math.atan2(norm(cross(a, b)), dot(a, b));
// A direction this far outside a triangle's edge plane still counts as inside (rounding).
const edgeTolerance = 1e-12;

export class LightInterpolation {
  // cover: the manifest's light_cover; lights: the field's light count.
  constructor(cover, lights) {
    this.lights = lights;
    this.directions = cover.directions;
    this.lightsOf = cover.lights_of;
    this.triangles = cover.triangles;
    this.rim = cover.rim;
    // Inward normals of each triangle's edge planes.
    this.cones = this.triangles.map((t) =>
      [0, 1, 2].map((e) => cross(this.directions[t[e]], this.directions[t[(e + 1) % 3]])));
  }

  containingTriangle(d) {
    for (let t = 0; t < this.cones.length; ++t) {
      const n = this.cones[t];
      if (dot(n[0], d) >= -edgeTolerance && dot(n[1], d) >= -edgeTolerance &&
          dot(n[2], d) >= -edgeTolerance)
        return t;
    }
    return -1;
  }

  // True when a triangle holds the direction (else it takes the rim's weights).
  covers(direction) {
    return this.containingTriangle(unit(direction)) >= 0;
  }

  addPointWeights(d, scale, distinct) {
    const t = this.containingTriangle(d);
    if (t < 0) return this.addRimWeights(d, scale, distinct);
    const corners = this.triangles[t], n = this.cones[t];
    const coefficient = [0, 0, 0];
    let sum = 0;
    for (let e = 0; e < 3; ++e) {
      const opposite = n[(e + 1) % 3];
      coefficient[e] = Math.max(0, dot(opposite, d) / dot(opposite, this.directions[corners[e]]));
      sum += coefficient[e];
    }
    for (let e = 0; e < 3; ++e) distinct[corners[e]] += scale * coefficient[e] / sum;
  }

  addRimWeights(d, scale, distinct) {
    let nearest = Math.PI * 2, first = -1, second = -1, firstShare = 1;
    for (const [a, b] of this.rim) {
      const pa = this.directions[a], pb = this.directions[b];
      const normal = unit(cross(pa, pb));
      const inPlane = d.map((v, k) => v - dot(d, normal) * normal[k]);
      if (norm(inPlane) > 1e-12) {
        const p = unit(inPlane);
        const alpha = dot(cross(p, pb), normal), beta = dot(cross(pa, p), normal);
        if (alpha >= 0 && beta >= 0 && angleBetween(d, p) < nearest) {
          nearest = angleBetween(d, p);
          first = a, second = b, firstShare = alpha / (alpha + beta);
        }
      }
      for (const end of [a, b])
        if (angleBetween(d, this.directions[end]) < nearest) {
          nearest = angleBetween(d, this.directions[end]);
          first = end, second = -1, firstShare = 1;
        }
    }
    if (first < 0) throw new Error(`light direction ${d} lies in no triangle of the light set`);
    distinct[first] += scale * firstShare;
    if (second >= 0) distinct[second] += scale * (1 - firstShare);
  }

  // One weight per light, non-negative, summing to one, for a point light from `direction`
  // (camera frame: x right, y up, z towards the camera; need not be unit).
  weights(direction) {
    if (!direction.every(Number.isFinite) || !(norm(direction) > 0))
      throw new Error(`light direction ${direction} is zero or not finite`);
    const distinct = new Float64Array(this.directions.length);
    this.addPointWeights(unit(direction), 1, distinct);
    const result = new Float64Array(this.lights);
    this.lightsOf.forEach((lights, j) => {
      for (const light of lights) result[light] = distinct[j] / lights.length;
    });
    return result;
  }

  // The light vector (lights x 3, RGB, float) of a light of colour `rgb` from `direction`.
  lightVector(direction, rgb = [1, 1, 1]) {
    const w = this.weights(direction);
    const vector = new Float32Array(this.lights * 3);
    for (let i = 0; i < this.lights; ++i)
      for (let c = 0; c < 3; ++c) vector[i * 3 + c] = w[i] * rgb[c];
    return vector;
  }
}

// The light vectors of an environment map turned about the up axis, as LightVectorIntegrator
// (lib/lighting/light_vector.cpp) makes them: each sample (a lat-long cell's centre direction
// and its energy, radiance x solid angle) goes to the nearest light (the largest dot product, the
// lowest index among equals) when that light is within the coverage radius; turning the map by
// an angle turns the lights by minus it.
export class EnvironmentLighting {
  // cover: the manifest's light_cover; lights: the field's light count; map: a manifest
  // environment entry; energy: its RGB energies, rows x columns x 3.
  constructor(cover, lights, map, energy) {
    this.lights = lights;
    this.lightDirections = new Array(lights);
    cover.lights_of.forEach((list, j) => {
      for (const light of list) this.lightDirections[light] = cover.directions[j];
    });
    this.coveredDot = Math.cos(cover.coverage_radius);
    this.samples = [];
    for (let y = 0; y < map.height; ++y)
      for (let x = 0; x < map.width; ++x) {
        const k = (y * map.width + x) * 3;
        if (energy[k] === 0 && energy[k + 1] === 0 && energy[k + 2] === 0) continue;
        const theta = Math.PI * ((y + 0.5) / map.height);
        const phi = 2 * Math.PI * ((x + 0.5) / map.width - 0.5);
        this.samples.push({
          direction: [Math.sin(phi) * Math.sin(theta), Math.cos(theta), -Math.cos(phi) * Math.sin(theta)],
          energy: [energy[k], energy[k + 1], energy[k + 2]],
        });
      }
  }

  // The light vector (lights x 3, RGB, float) of the map turned by `degrees` about +y
  // (counter-clockwise seen from above).
  lightVector(degrees) {
    const angle = (-degrees * Math.PI) / 180, c = Math.cos(angle), s = Math.sin(angle);
    const turned = this.lightDirections.map(([x, y, z]) => [c * x + s * z, y, -s * x + c * z]);
    const sums = new Float64Array(this.lights * 3);
    for (const { direction, energy } of this.samples) {
      let best = -1, bestDot = -2;
      for (let l = 0; l < turned.length; ++l) {
        const d = dot(direction, turned[l]);
        if (d > bestDot) bestDot = d, best = l;
      }
      if (bestDot < this.coveredDot) continue;
      for (let k = 0; k < 3; ++k) sums[best * 3 + k] += energy[k];
    }
    return Float32Array.from(sums);
  }
}

// lib/model/haar_transform.cpp's haar_forward on values[0], values[stride], ... in float.
const inverseSqrt2 = f32(0.70710678118654752440);
function haarForward(values, count, stride) {
  const level = new Float32Array(count);
  for (let n = count; n > 1; n = (n + 1) >> 1) {
    const pairs = n >> 1, averages = (n + 1) >> 1;
    for (let k = 0; k < pairs; ++k) {
      const a = values[2 * k * stride], b = values[(2 * k + 1) * stride];
      level[k] = f32(f32(a + b) * inverseSqrt2);
      level[averages + k] = f32(f32(a - b) * inverseSqrt2);
    }
    if (n % 2 === 1) level[pairs] = values[(n - 1) * stride];
    for (let i = 0; i < n; ++i) values[i * stride] = level[i];
  }
}

// The light vector in the field's basis (lights x channels), as light_in_field_basis in
// lib/relight/compressed_relight_reference.cpp: a one-channel field is lit by the mean of R, G
// and B; a Haar field by the vector's Haar transform over the lights.
export function lightInFieldBasis(field, vector) {
  const channels = field.channels, lights = field.lights;
  const basis = new Float32Array(lights * channels);
  for (let i = 0; i < lights; ++i)
    if (channels === 1)
      basis[i] = f32(f32(f32(vector[i * 3] + vector[i * 3 + 1]) + vector[i * 3 + 2]) / 3);
    else
      for (let c = 0; c < 3; ++c) basis[i * 3 + c] = vector[i * 3 + c];
  if (field.transform === 'haar')
    for (let c = 0; c < channels; ++c) haarForward(basis.subarray(c), lights, channels);
  return basis;
}
