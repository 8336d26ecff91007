#version 450
// Negative control of test_shader_stats: a kernel that cannot fit in registers. 96 vec4
// values a0..a7, b0..b7, ..., l7 are computed one from the other, then consumed in reverse
// order by a serial chain: the first use needs the last value, so all 4 x 96 = 384 are live at
// once, more than the 256 VGPRs a wave may have, and the compiler must spill to scratch on
// every chip. (Separate variables, not an array: an array would be placed in scratch memory
// without any spilling, which would test only half of the check.)
layout(local_size_x = 64) in;
layout(set = 0, binding = 0, std430) readonly buffer Source { vec4 source[]; };
layout(set = 0, binding = 1, std430) writeonly buffer Target { vec4 target[]; };

#define MAKE(name, index) vec4 name = sin(previous * 1.37f + source[base + uint(index)]); previous = name;
#define USE(name) chain = cos(chain * name + 0.5f);
#define MAKE8(g, n) MAKE(g##0, n * 8 + 0) MAKE(g##1, n * 8 + 1) MAKE(g##2, n * 8 + 2) MAKE(g##3, n * 8 + 3) \
                    MAKE(g##4, n * 8 + 4) MAKE(g##5, n * 8 + 5) MAKE(g##6, n * 8 + 6) MAKE(g##7, n * 8 + 7)
#define USE8(g) USE(g##7) USE(g##6) USE(g##5) USE(g##4) USE(g##3) USE(g##2) USE(g##1) USE(g##0)

void main()
{
    uint base = gl_GlobalInvocationID.x * 256u;
    vec4 previous = source[base];
    MAKE8(a, 0) MAKE8(b, 1) MAKE8(c, 2) MAKE8(d, 3) MAKE8(e, 4) MAKE8(f, 5)
    MAKE8(g, 6) MAKE8(h, 7) MAKE8(i, 8) MAKE8(j, 9) MAKE8(k, 10) MAKE8(l, 11)
    vec4 chain = vec4(0.0f);
    USE8(l) USE8(k) USE8(j) USE8(i) USE8(h) USE8(g) USE8(f) USE8(e) USE8(d) USE8(c) USE8(b) USE8(a)
    target[gl_GlobalInvocationID.x] = chain;
}
