/* ggx.c: GGX, the Trowbridge-Reitz microfacet lobe (SPEC §9.2, §9.3), in
 * sr^-1, with its --fresnel and --smith variants.
 *
 * References:
 *   [1] B. Walter, S. R. Marschner, H. Li, K. E. Torrance, "Microfacet
 *       models for refraction through rough surfaces", EGSR 2007
 *       (eq. 20 the lobe, eq. 33 D, eq. 34 Lambda).
 *   [2] E. Heitz, JCGT 3(2), 2014 (eq. 99 height-correlated G2, eq. 98
 *       separable).
 *
 * Equations (microfacet.h has the pieces and the frame, smith_lobe.h the
 * lobe and its variants):
 *   GGX = rho_s F(cos theta_d) D(h) G2(i, o, h) / (4 cos ti cos to)
 *                                                   SPEC §9.2, §9.3
 *   D = alpha^2 / (pi cos^4 th (alpha^2 + tan^2 th)^2)  Walter eq. 33
 *   Lambda(v) = (-1 + sqrt(1 + alpha^2 tan^2 tv)) / 2   Walter eq. 34
 *   G2 = 1 / (1 + Lambda(i) + Lambda(o))                Heitz eq. 99
 *      or G1(i) G1(o), G1 = 1 / (1 + Lambda)            Heitz eq. 98
 *   F = Schlick(F0), dielectric(n) (SPEC §4.1) or 1     SPEC §9.2
 * Limits: finite on the closed hemisphere; at one grazing zenith the
 * value is its limit (c Lambda stays finite, microfacet.h); 0 at the
 * grazing corner ti = to = pi/2.
 */
#include "models/smith_lobe.h"

BF__SMITH_FAMILY(ggx, BF__NDF_GGX, "GGX", "GGX",
                 "GGX (Trowbridge-Reitz) microfacet lobe, sr^-1",
                 "Walter et al. 2007 eqs. 20, 33, 34; "
                 "Heitz 2014 eqs. 98-99; SPEC §9.2, §9.3",
                 BF__STYLE_GGX);
