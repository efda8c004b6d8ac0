/* Fuzz target of the case loader: any bytes are either a valid case or an input error, never a
 * crash, a leak or undefined behaviour. Built with libFuzzer under clang, or run by fuzz_main.c. */
#include <stddef.h>
#include <stdint.h>

#include "pmech/case.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pm_case c;
    pm_case_load_buffer((const char *)data, size, "fuzz/case.json", &c);
    pm_case_free(&c);
    return 0;
}
