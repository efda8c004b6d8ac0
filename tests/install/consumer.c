/* A program outside the tree that uses the installed library through pmech.h and pkg-config. */
#include <pmech/pmech.h>
#include <stdio.h>

int main(void)
{
    const char *const *m = pm_material_names();
    printf("%s\n", m[0]);
    return pm_material_find("linear_elastic") ? 0 : 1;
}
