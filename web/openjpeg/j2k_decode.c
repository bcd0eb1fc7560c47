// j2k_decode.c: the published page's JPEG 2000 decoder, OpenJPEG built for WebAssembly by
// scripts/build_openjpeg_wasm.sh into j2k_decode.js and j2k_decode.wasm beside this file (the
// page's web/weight_planes.js calls it). It decodes a one-basis container's weight planes (one raw
// codestream of signed 16-bit components: lib/container/jpeg2000_planes.cpp) whole, held in
// memory, as relume's own reader does (OpenJPEG in strict mode, so that a truncated codestream is
// an error, not planes with missing detail), into signed 16-bit planes, and keeps OpenJPEG's
// error messages for the page's status line.
#include <openjpeg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// What j2k_decode returns: `count` planes of width x height samples, plane after plane, each
// row-major, from `samples` on.
typedef struct {
  int32_t count, width, height;
  int16_t* samples;
} DecodedPlanes;

static char errors[1024];

static void keep_error(const char* message, void* client) {
  (void)client;
  const size_t used = strlen(errors);
  snprintf(errors + used, sizeof errors - used, "%s%s", used ? "; " : "", message);
  for (size_t end = strlen(errors); end > 0 && (errors[end - 1] == '\n' || errors[end - 1] == ' ');)
    errors[--end] = '\0';
}

static void ignore_message(const char* message, void* client) {
  (void)message;
  (void)client;
}

static void fail(const char* message) { snprintf(errors, sizeof errors, "%s", message); }

// The codestream held in memory, read by OpenJPEG's stream callbacks.
typedef struct {
  const uint8_t* data;
  size_t size, position;
} MemoryInput;

static OPJ_SIZE_T read_memory(void* buffer, OPJ_SIZE_T size, void* user) {
  MemoryInput* in = user;
  if (in->position >= in->size) return (OPJ_SIZE_T)-1;
  const size_t n = size < in->size - in->position ? size : in->size - in->position;
  memcpy(buffer, in->data + in->position, n);
  in->position += n;
  return n;
}

static OPJ_OFF_T skip_input(OPJ_OFF_T size, void* user) {
  MemoryInput* in = user;
  OPJ_OFF_T to = (OPJ_OFF_T)in->position + size;
  if (to < 0) to = 0;
  if (to > (OPJ_OFF_T)in->size) to = (OPJ_OFF_T)in->size;
  const OPJ_OFF_T moved = to - (OPJ_OFF_T)in->position;
  in->position = (size_t)to;
  return moved;
}

static OPJ_BOOL seek_input(OPJ_OFF_T position, void* user) {
  MemoryInput* in = user;
  if (position < 0 || (uint64_t)position > in->size) return OPJ_FALSE;
  in->position = (size_t)position;
  return OPJ_TRUE;
}

// Whether every component is a whole-resolution signed plane of at most 16 bits, as large as the
// first; says which is not otherwise.
static int signed_16_bit_planes(const opj_image_t* image) {
  for (OPJ_UINT32 c = 0; c < image->numcomps; ++c) {
    const opj_image_comp_t* component = &image->comps[c];
    if (component->dx != 1 || component->dy != 1 || !component->sgnd || component->prec > 16 ||
        component->w != image->comps[0].w || component->h != image->comps[0].h) {
      snprintf(errors, sizeof errors,
               "plane %u is %s %u-bit, %ux%u with sub-sampling %ux%u, expected signed planes of "
               "at most 16 bits, all of one size",
               c, component->sgnd ? "signed" : "unsigned", component->prec, component->w,
               component->h, component->dx, component->dy);
      return 0;
    }
  }
  return 1;
}

// Moves the decoded components into one block of 16-bit samples, freeing each component's own
// 32-bit samples as it goes; NULL when out of memory.
static DecodedPlanes* planes_of(opj_image_t* image) {
  const size_t area = (size_t)image->comps[0].w * image->comps[0].h;
  DecodedPlanes* planes = malloc(sizeof *planes);
  int16_t* samples = malloc(area * image->numcomps * sizeof *samples);
  if (!planes || !samples) {
    free(planes);
    free(samples);
    fail("out of memory for the decoded planes");
    return NULL;
  }
  planes->count = (int32_t)image->numcomps;
  planes->width = (int32_t)image->comps[0].w;
  planes->height = (int32_t)image->comps[0].h;
  planes->samples = samples;
  for (OPJ_UINT32 c = 0; c < image->numcomps; ++c) {
    const OPJ_INT32* from = image->comps[c].data;
    int16_t* to = samples + c * area;
    // OpenJPEG clamps each sample to its component's precision: the narrowing loses nothing.
    for (size_t i = 0; i < area; ++i) to[i] = (int16_t)from[i];
    opj_image_data_free(image->comps[c].data);
    image->comps[c].data = NULL;
  }
  return planes;
}

// Decodes the raw codestream data[0, size) whole. Returns the planes (free them with
// j2k_free_planes) or NULL, with the reason in j2k_errors().
DecodedPlanes* j2k_decode(const uint8_t* data, size_t size) {
  errors[0] = '\0';
  opj_codec_t* codec = opj_create_decompress(OPJ_CODEC_J2K);
  opj_stream_t* stream = opj_stream_create(OPJ_J2K_STREAM_CHUNK_SIZE, OPJ_TRUE);
  if (!codec || !stream) {
    if (codec) opj_destroy_codec(codec);
    if (stream) opj_stream_destroy(stream);
    fail("cannot create the JPEG 2000 decoder");
    return NULL;
  }
  opj_set_error_handler(codec, keep_error, NULL);
  opj_set_warning_handler(codec, ignore_message, NULL);
  opj_set_info_handler(codec, ignore_message, NULL);
  MemoryInput in = {data, size, 0};
  opj_stream_set_user_data(stream, &in, NULL);
  opj_stream_set_user_data_length(stream, size);
  opj_stream_set_read_function(stream, read_memory);
  opj_stream_set_skip_function(stream, skip_input);
  opj_stream_set_seek_function(stream, seek_input);
  opj_dparameters_t parameters;
  opj_set_default_decoder_parameters(&parameters);
  opj_image_t* image = NULL;
  DecodedPlanes* planes = NULL;
  if (!opj_setup_decoder(codec, &parameters) || !opj_decoder_set_strict_mode(codec, OPJ_TRUE)) {
    if (!errors[0]) fail("cannot set up the JPEG 2000 decoder");
  } else if (!opj_read_header(stream, codec, &image)) {
    if (!errors[0]) fail("not a JPEG 2000 codestream");
  } else if (signed_16_bit_planes(image)) {
    if (opj_decode(codec, stream, image) && opj_end_decompress(codec, stream))
      planes = planes_of(image);
    else if (!errors[0])
      fail("the codestream does not decode");
  }
  if (image) opj_image_destroy(image);
  opj_stream_destroy(stream);
  opj_destroy_codec(codec);
  return planes;
}

void j2k_free_planes(DecodedPlanes* planes) {
  if (!planes) return;
  free(planes->samples);
  free(planes);
}

// Why the last j2k_decode returned NULL: OpenJPEG's error messages, or this file's own.
const char* j2k_errors(void) { return errors; }
