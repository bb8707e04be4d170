/* beckmann.c: BECKMANN, the microfacet lobe with Beckmann's normal
 * distribution (SPEC §9.2, §9.3), in sr^-1, with its --fresnel and
 * --smith variants.
 *
 * References:
 *   [1] B. Walter, S. R. Marschner, H. Li, K. E. Torrance, "Microfacet
 *       models for refraction through rough surfaces", EGSR 2007
 *       (eq. 20 the lobe, eq. 25 D, eq. 26 Lambda in its exact erf form,
 *       not the rational approximation of eq. 27).
 *   [2] E. Heitz, JCGT 3(2), 2014 (eq. 99 height-correlated G2, eq. 98
 *       separable).
 *
 * Equations (microfacet.h has the pieces and the frame, smith_lobe.h the
 * lobe and its variants):
 *   BECKMANN = rho_s F(cos theta_d) D(h) G2(i, o, h) / (4 cos ti cos to)
 *                                                   SPEC §9.2, §9.3
 *   D = exp(-tan^2 th / alpha^2) / (pi alpha^2 cos^4 th)  Walter eq. 25
 *   Lambda(v) = (erf(a) - 1)/2 + exp(-a^2) / (2 a sqrt(pi)),
 *       a = 1 / (alpha tan tv)                       Walter eq. 26, SPEC §9.2
 *   G2 = 1 / (1 + Lambda(i) + Lambda(o))                Heitz eq. 99
 *      or G1(i) G1(o), G1 = 1 / (1 + Lambda)            Heitz eq. 98
 *   F = Schlick(F0), dielectric(n) (SPEC §4.1) or 1     SPEC §9.2
 * Limits: finite on the closed hemisphere; at one grazing zenith the
 * value is its limit (c Lambda stays finite, microfacet.h); 0 at the
 * grazing corner ti = to = pi/2.
 */
#include "models/smith_lobe.h"

BF__SMITH_FAMILY(beckmann, BF__NDF_BECKMANN, "BECKMANN", "Beckmann",
                 "Beckmann microfacet lobe (exact Smith Lambda), sr^-1",
                 "Walter et al. 2007 eqs. 20, 25, 26; "
                 "Heitz 2014 eqs. 98-99; SPEC §9.2, §9.3",
                 BF__STYLE_BECKMANN);
