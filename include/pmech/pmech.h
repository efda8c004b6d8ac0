/**
 * @file pmech.h
 * @brief All of pmech's public interface: include this one header.
 */
#ifndef PMECH_PMECH_H
#define PMECH_PMECH_H

#include "pmech/approx.h"
#include "pmech/case.h"
#include "pmech/driver.h"
#include "pmech/error.h"
#include "pmech/grid.h"
#include "pmech/material.h"
#include "pmech/particles.h"
#include "pmech/render.h"
#include "pmech/sim.h"
#include "pmech/strength_reduction.h"
#include "pmech/timefn.h"

#endif
