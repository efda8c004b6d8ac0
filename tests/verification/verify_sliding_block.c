/*
 * A block sliding on a frictional grid boundary under gravity tilted by theta = 30 degrees
 * (Coulomb friction of Bardenhagen et al. 2000). Rigid-body answer: the mean velocity along the
 * base is g (sin(theta) - mu cos(theta)) t while sliding: 0.4905 m/s (mu = 0) and 0.40554 m/s
 * (mu = 0.1) at t = 0.1 s, compared within 2 % (the elastic block rings a little at the start).
 * With mu = 1.5 tan(theta) it sticks: its centre of mass must move less than 2 % of the
 * frictionless distance g sin(theta) t^2 / 2.
 * The same three rows with scheme usl (cases/sliding_block_usl.json), the same tolerances: USL took
 * the strain rate from the end-of-step velocity of a node the block's front face had only just
 * reached (2e-5 of a particle's mass) and diverged at t = 0.029 s (mu = 0, and with a plain roller
 * side instead of friction) and 0.032 s (mu = 0.1); such nodes now add only part of their increment
 * (src/solver/explicit_grid.c).
 */
#include "verify_util.h"

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    int ok = vu_sliding_block("sliding block", "tests/verification/cases/sliding_block.json", "", vu_run_to, 0.02);
    ok &= vu_sliding_block("sliding block, usl", "tests/verification/cases/sliding_block_usl.json", "", vu_run_to,
                           0.02);
    return ok ? 0 : 1;
}
