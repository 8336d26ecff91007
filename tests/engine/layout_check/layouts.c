// Structs declared with rtpbr_shared.h's mechanism, compiled by test_layout_check.sh with
// -DLAYOUT_CASE=n: case 0 is laid out as std140/std430 would and must compile; every other
// case misplaces one member (or the size) and must fail with the check's message.
#include "rtpbr_shared.h"

#if LAYOUT_CASE == 0 // correct: vec3 + float share 16 bytes, uvec2 on 8, size 48
#define FIELDS(F, S)                                                                              \
    F(S, VEC3, direction, )                                                                        \
    F(S, FLOAT, length, )                                                                          \
    F(S, VEC4, colour, [1])                                                                        \
    F(S, UINT, count, )                                                                            \
    F(S, UINT, pad0, )                                                                             \
    F(S, UVEC2, size, )
#elif LAYOUT_CASE == 1 // a vec4 after one float: C puts it at 4, the shaders at 16
#define FIELDS(F, S)                                                                              \
    F(S, FLOAT, length, )                                                                          \
    F(S, VEC4, colour, )                                                                           \
    F(S, UINT, pad0, )                                                                             \
    F(S, UINT, pad1, )                                                                             \
    F(S, UINT, pad2, )
#elif LAYOUT_CASE == 2 // two vec3 in a row: C puts the second at 12, the shaders at 16
#define FIELDS(F, S)                                                                              \
    F(S, VEC3, direction, )                                                                        \
    F(S, VEC3, normal, )                                                                           \
    F(S, FLOAT, pad0, )                                                                            \
    F(S, FLOAT, pad1, )                                                                            \
    F(S, FLOAT, pad2, )                                                                            \
    F(S, FLOAT, pad3, )
#elif LAYOUT_CASE == 3 // a uvec2 after one uint: C puts it at 4, the shaders at 8
#define FIELDS(F, S)                                                                              \
    F(S, UINT, count, )                                                                            \
    F(S, UVEC2, size, )                                                                            \
    F(S, UINT, pad0, )                                                                             \
    F(S, UINT, pad1, )                                                                             \
    F(S, UINT, pad2, )
#elif LAYOUT_CASE == 4 // 20 bytes: an array of these would be strided 32 by the shaders
#define FIELDS(F, S)                                                                              \
    F(S, VEC4, colour, )                                                                           \
    F(S, FLOAT, length, )
#endif

RTPBR_SHARED_STRUCT(layout_under_test, FIELDS)
RTPBR_SHARED_CHECK_LAYOUT(layout_under_test, FIELDS)
