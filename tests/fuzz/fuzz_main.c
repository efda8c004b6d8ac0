/*
 * Stand-alone driver of the fuzz target for compilers without libFuzzer (gcc): runs every seed, then
 * deterministic mutations of the seeds (byte flips, deletions, insertions of JSON tokens, splices,
 * truncations) from a fixed-seed generator, for a bounded count and time. Under ctest the build's
 * sanitizers (make asan) turn any memory error into a failure; in the default build a crash fails.
 * usage: fuzz_main SECONDS ITERATIONS SEED_FILE...
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static uint64_t rng = 0x9E3779B97F4A7C15ull;
static uint64_t next(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng;
}

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)n + 1);
    if (b && fread(b, 1, (size_t)n, f) != (size_t)n) {
        free(b);
        b = NULL;
    }
    fclose(f);
    *len = (size_t)n;
    return b;
}

static const char *const tokens[] = {"{", "}", "[", "]", ",", ":", "\"", "null", "true", "-1", "1e308", "0",
                                     "\"type\"", "\"rectangle\"", "\"circle\"", "\"polygon\"", "[[0,0],[1,0]]",
                                     "1e-320", "\"x_min\"", "{\"x\": 1}", "NaN", "99999999999999999999"};

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: fuzz_main SECONDS ITERATIONS SEED_FILE...\n");
        return 2;
    }
    const double seconds = atof(argv[1]);
    const long iterations = atol(argv[2]);
    int nseeds = argc - 3;
    char **seeds = calloc((size_t)nseeds, sizeof *seeds);
    size_t *lens = calloc((size_t)nseeds, sizeof *lens);
    size_t maxlen = 0;
    for (int k = 0; k < nseeds; k++) {
        seeds[k] = slurp(argv[3 + k], &lens[k]);
        if (!seeds[k]) {
            fprintf(stderr, "cannot read %s\n", argv[3 + k]);
            return 2;
        }
        LLVMFuzzerTestOneInput((const uint8_t *)seeds[k], lens[k]);
        if (lens[k] > maxlen)
            maxlen = lens[k];
    }
    const size_t cap = 2 * maxlen + 256;
    uint8_t *buf = malloc(cap);
    const clock_t start = clock();
    long it = 0;
    for (; it < iterations; it++) {
        if ((double)(clock() - start) / CLOCKS_PER_SEC > seconds)
            break;
        int s = (int)(next() % (uint64_t)nseeds);
        size_t len = lens[s];
        memcpy(buf, seeds[s], len);
        int edits = 1 + (int)(next() % 8);
        for (int e = 0; e < edits && len > 0; e++) {
            size_t at = next() % len;
            switch (next() % 6) {
            case 0: buf[at] ^= (uint8_t)(1u << (next() % 8)); break;
            case 1: buf[at] = (uint8_t)next(); break;
            case 2: /* delete a run */ {
                size_t n = 1 + next() % 16;
                if (at + n > len)
                    n = len - at;
                memmove(buf + at, buf + at + n, len - at - n);
                len -= n;
                break;
            }
            case 3: /* insert a JSON token */ {
                const char *t = tokens[next() % (sizeof tokens / sizeof tokens[0])];
                size_t n = strlen(t);
                if (len + n < cap) {
                    memmove(buf + at + n, buf + at, len - at);
                    memcpy(buf + at, t, n);
                    len += n;
                }
                break;
            }
            case 4: /* splice from another seed */ {
                int o = (int)(next() % (uint64_t)nseeds);
                size_t from = next() % lens[o], n = 1 + next() % 64;
                if (from + n > lens[o])
                    n = lens[o] - from;
                if (at + n <= cap)
                    memcpy(buf + at, seeds[o] + from, n);
                if (at + n > len)
                    len = at + n;
                break;
            }
            default: len = at; break;
            }
        }
        LLVMFuzzerTestOneInput(buf, len);
    }
    printf("fuzz_main: %ld inputs from %d seeds, no crash\n", it, nseeds);
    for (int k = 0; k < nseeds; k++)
        free(seeds[k]);
    free(seeds);
    free(lens);
    free(buf);
    return 0;
}
