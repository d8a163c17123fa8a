// Ground-Truth Specular Occlusion (Jimenez et al. 2016, §6 and App. B): the share of a specular lobe that
// the visibility cone lets through. The visibility cone has the bent normal as axis and the aperture that
// gives the pixel's AO (eq. 17-18); the specular lobe is either a cone about the reflection direction
// (eq. 25-26, intersected analytically, eq. 19) or the GGX BRDF itself, integrated once into a table
// (eq. 21).
//
// Table convention (the paper leaves it open): normal n = +Z, view direction w_o at polar angle theta_o in
// the XZ plane (azimuth pi), reflection w_r = (sin theta_o, 0, cos theta_o), and the bent normal b in the
// same plane, beta from w_r rotated towards n. The BRDF is GGX with height-correlated Smith masking and no
// Fresnel: it cancels in eq. 14 where it depends on w_o alone, as the paper's eq. 4 takes it (a Schlick
// F(v.h) with F0 = 0.04 would move eq. 21 by up to 0.2 at grazing views); GGX alpha = roughness^2. The 4-D table's beta nodes follow b from w_r
// (beta = 0) to n (beta = theta_o, node 15 at every theta_o) and on to the horizon (beta = theta_o + pi/2,
// node 31), so that b = n, where S falls steeply at grazing views, is a node rather than a point between two.
//
// Errors: the per-point functions check nothing (a hot path): inputs are clamped into the tables' ranges,
// and a NaN input gives NaN. computeSpecularOcclusion throws obscura::Error on bad input (below). The tables
// are computed on first use, once per process (thread-safe), by importance sampling the visible normals of
// GGX (Heitz 2018): about 0.5 s.
#pragma once

#include "obscura/gbuffer.h"
#include "obscura/image.h"
#include "obscura/math.h"

#include <vector>

namespace obscura::ssao {

// eq. 18: cos of the visibility cone's half-angle for cosine-weighted AO, sqrt(1 - A). Every function here
// takes cosine-weighted AO: GTAO with GtaoWeighting::Uniform gives uniformly weighted A, whose cone is App. A's
// eq. 24, cos = 1 - A (at A = 0.5, 60 degrees, where eq. 18 gives 45), which is not implemented.
float visibilityConeCos(float ao);
// eq. 18's half-angle alpha_v itself (radians, [0, pi/2]), precise for AO near 0 where acos of the cosine is not.
float visibilityConeAngle(float ao);
// eq. 26: cos of the specular cone's half-angle, 0.01^(r^2 / 2) = exp(-2.30259 r^2).
float specularConeCos(float roughness);
// Solid angle of the intersection of two spherical caps of half-angles alpha1, alpha2 (radians, [0, pi])
// whose axes are beta apart ([0, pi]) (Tovchigrechko and Vakser 2001; Mazonka 2012), computed in double in a
// form that keeps its relative precision for caps of any size (a specular cone of roughness 0.001 included).
float capIntersectionSolidAngle(float alpha1, float alpha2, float beta);
// eq. 19: Omega_i / Omega_s for the cone about w_r, beta = angle(b, w_r). Roughness 0 is a mirror: 1 where
// beta < alpha_v, else 0 (so 0 for AO = 0).
float specularOcclusionCone(float alphaV, float beta, float roughness);

constexpr int kSpecularTableSize = 32;  // samples per dimension (32^4 and 32^3 entries)

class SpecularOcclusionTable {
public:
    // 4-D S(alpha_v, beta, roughness, theta_o) of eq. 21, and the 3-D variant with b = n (beta = theta_o).
    static const SpecularOcclusionTable& fourD();
    static const SpecularOcclusionTable& threeD();

    // Multilinear lookup. alpha_v in [0, pi/2], beta in [0, theta_o + pi/2], roughness in [0, 1], theta_o in
    // [0, pi/2]; values outside are clamped, NaN gives NaN. The 3-D table ignores beta (it is theta_o there).
    float lookup(float alphaV, float beta, float roughness, float thetaO) const;
    // The value stored at grid node (i, j, k, l) (alpha_v, beta, roughness, theta_o); j ignored in 3-D.
    float node(int i, int j, int k, int l) const;
    static float alphaVAt(int i);
    static float betaAt(int j, float thetaO);  // the beta of node j at that theta_o (see the convention above)
    static float roughnessAt(int k);
    static float thetaOAt(int l);
    bool isFourD() const { return fourD_; }

private:
    explicit SpecularOcclusionTable(bool fourD);
    bool fourD_;
    std::vector<float> values_;
};

enum class SpecularOcclusionMode { Lut4, Lut3, Cone };

// S for one shading point; all vectors unit, in one space; view points from the surface to the eye. Lut3 takes
// the normal to be the bent normal (§6): it reads the 3-D table at beta = angle(b, w_r) for theta_o too.
float specularOcclusion(SpecularOcclusionMode mode, float ao, Vec3 bentNormal, Vec3 normal, Vec3 view,
                        float roughness);

// computeSpecularOcclusion's checks, which gpu::specularOcclusion makes too (the same messages): roughness in
// [0, 1]; AO and bent normal of the G-buffer's size (1 and 3 channels); the G-buffer's depth and normal of its
// camera's size (1 and 3 channels), its depths positive or +inf and its normals finite; AO and bent normal
// finite on every surface pixel (sky pixels are not read). Throws obscura::Error naming the first problem.
void checkSpecularOcclusionInputs(const GBuffer& gbuffer, const Image& ao, const Image& bentNormal, float roughness);

// Per pixel from a G-buffer, its AO and bent normals (view space), with one roughness for every pixel
// (the G-buffer carries none). Sky pixels get 1. Throws obscura::Error as checkSpecularOcclusionInputs says.
Image computeSpecularOcclusion(const GBuffer& gbuffer, const Image& ao, const Image& bentNormal,
                               SpecularOcclusionMode mode, float roughness);

} // namespace obscura::ssao
