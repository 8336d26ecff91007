// The outputs of the GPU test kernel (kernel.h): one section per shaderlib header.
// No include guard: kernel.h includes this list several times, each time with its own
// RTPBR_TEST_CASE(name, expression). `name` is an identifier (reported by the test; vector
// components end in _x, _y, _z), `expression` a float built from the fields of `t`
// (RtpbrTestArgs, kernel.h) and any shaderlib function.
//
// To cover a new header (kulla_conty.h, ltc.h, disney.h, ...):
//   1. include it at the top of kernel.h (and list it in meson.build's kernel_sources);
//   2. write cases/<header>.inc with one RTPBR_TEST_CASE per public function (one per
//      component of a vector result), arguments mapped into the function's domain from the
//      fields of RtpbrTestArgs (add fields to RtpbrTestArgs if a new domain is needed, derived
//      with + - * / sqrt only);
//   3. add its #include line below.
// Nothing else changes: the count, the names and both shader languages follow from this list.
#include "cases/fresnel.inc"
#include "cases/ndf.inc"
#include "cases/smith.inc"
#include "cases/microfacet.inc"
#include "cases/sampling.inc"
#include "cases/ltc.inc"
#include "cases/material.inc"
#include "cases/kulla_conty.inc"
