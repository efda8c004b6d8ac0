/*
 * Principal-stress helpers for isotropic return mappings: eigen-decomposition of a symmetric 3x3
 * tensor in Voigt form and the spectral form of the consistent tangent of an isotropic stress
 * update sigma = f(sigma_trial).
 */
#ifndef PMECH_MATERIAL_PRINCIPAL_H
#define PMECH_MATERIAL_PRINCIPAL_H

/**
 * @brief Eigenvalues and eigenvectors of a symmetric tensor (cyclic Jacobi, accurate to round-off).
 * @param s Voigt tensor (xx, yy, zz, xy, yz, xz), shears as tensor components
 * @param lam receives the eigenvalues sorted lam[0] >= lam[1] >= lam[2]
 * @param V receives the unit eigenvectors as columns: V[3*i + a] is component i of vector a
 */
void pm_eig_sym3(const double s[6], double lam[3], double V[9]);

/**
 * @brief Voigt tensor sum_a lam[a] v_a (x) v_a from eigenvalues and eigenvectors (columns of V).
 */
void pm_spectral_compose(const double lam[3], const double V[9], double s[6]);

/**
 * @brief Consistent tangent (6x6 row-major, engineering shear strains) of an isotropic stress update.
 *
 * The trial stress is sigma_tr = sigma_0 + De : deps with isotropic De (shear modulus @p G) and
 * principal directions V; the update returns principal stresses sig[a] = f_a(str) in the same
 * directions. The tangent is
 *   D = sum_ab Dp[a][b] m_a (x) m_b + sum_{a<b} 2 c_ab M_ab (x) M_ab,
 *   c_ab = 2G (sig_a - sig_b) / (str_a - str_b)     (limit (Dp_aa - Dp_ab - Dp_ba + Dp_bb)/2),
 * with m_a = v_a (x) v_a and M_ab = (v_a (x) v_b + v_b (x) v_a) / 2.
 * @param V principal directions (columns)
 * @param str trial principal stresses
 * @param sig returned principal stresses
 * @param Dp 3x3 row-major principal tangent d sig_a / d eps_b (principal strains)
 * @param G elastic shear modulus of De
 * @param D receives the 6x6 tangent
 */
void pm_spectral_tangent(const double V[9], const double str[3], const double sig[3],
                         const double Dp[9], double G, double D[36]);

#endif
