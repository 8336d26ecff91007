// rtpbr-lut-export: writes every lookup table of the generated headers as a raw file (the
// data files installed in share/rtpbr/luts/, layout in luts-README.md there): little-endian
// IEEE float32, no header, the C array's element order. Build-time only (not installed).
//   rtpbr-lut-export OUTDIR
#include <stdio.h>
#include <string.h>

#include "rtpbr_kc_tables.h"
#include "rtpbr_ltc_sheen_tables.h"
#include "rtpbr_ltc_tables.h"
#include "rtpbr_sheen_tables.h"

#define TABLE(name) {#name, (const float *)(name), sizeof(name) / sizeof(float)}

static const struct {
    const char *name;
    const float *data;
    size_t count;
} tables[] = {
    TABLE(rtpbr_ltc_ggx_1),        TABLE(rtpbr_ltc_ggx_2),
    TABLE(rtpbr_ltc_beckmann_1),   TABLE(rtpbr_ltc_beckmann_2),
    TABLE(rtpbr_ltc_disney_diffuse_1), TABLE(rtpbr_ltc_disney_diffuse_2),
    TABLE(rtpbr_ltc_sheen_1),      TABLE(rtpbr_ltc_sheen_2),
    TABLE(rtpbr_kc_E),             TABLE(rtpbr_kc_Eavg),
    TABLE(rtpbr_kc_EF),            TABLE(rtpbr_kc_EFavg),
    TABLE(rtpbr_sheen_E),
};

int main(int argc, char **argv)
{
    static const char usage[] = "usage: rtpbr-lut-export OUTDIR\n"
                                "Writes every lookup table of the generated headers to OUTDIR/NAME.f32 (raw\n"
                                "little-endian float32, the C array's order). Build-time only.\n"
                                "  -h, --help  this text\n";
    if (argc == 2 && (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help"))) return fputs(usage, stdout), 0;
    if (argc != 2 || argv[1][0] == '-') return fputs(usage, stderr), 2;
    const unsigned probe = 1;
    if (*(const unsigned char *)&probe != 1) {
        fprintf(stderr, "rtpbr-lut-export: a big-endian host would need a byte swap here\n");
        return 1;
    }
    (void)rtpbr_kc_variant_names;
    for (size_t t = 0; t < sizeof tables / sizeof tables[0]; ++t) {
        char path[4096];
        if (snprintf(path, sizeof path, "%s/%s.f32", argv[1], tables[t].name) >= (int)sizeof path) {
            fprintf(stderr, "rtpbr-lut-export: output path too long\n");
            return 1;
        }
        FILE *f = fopen(path, "wb");
        if (!f) {
            fprintf(stderr, "rtpbr-lut-export: cannot write %s\n", path);
            return 1;
        }
        size_t written = fwrite(tables[t].data, sizeof(float), tables[t].count, f);
        if (fclose(f) != 0 || written != tables[t].count) {
            fprintf(stderr, "rtpbr-lut-export: writing %s failed\n", path);
            return 1;
        }
    }
    return 0;
}
