// Ground-Truth Specular Occlusion (Jimenez et al. 2016, §6 and App. B): the share of a specular lobe that
// the visibility cone lets through. The visibility cone has the bent normal as axis and the aperture that
// gives the pixel's AO (eq. 17-18); the specular lobe is either a cone about the reflection direction
// (eq. 25-26, intersected analytically, eq. 19) or the GGX BRDF itself, integrated once into a table
// (eq. 21).
//
// Table convention (the paper leaves it open): normal n = +Z, view direction w_o at polar angle theta_o in
// the XZ plane (azimuth pi), reflection w_r = (sin theta_o, 0, cos theta_o), and the bent normal b in the
// same plane, beta from w_r rotated towards n. The BRDF is GGX with height-correlated Smith masking and no
// Fresnel (it cancels in eq. 14); GGX alpha = roughness^2.
//
// Errors: none; inputs are clamped into the tables' ranges. The tables are computed on first use, once
// per process (thread-safe), by importance sampling the visible normals of GGX (Heitz 2018): about 0.5 s.
#pragma once

#include "obscura/gbuffer.h"
#include "obscura/image.h"
#include "obscura/math.h"

#include <vector>

namespace obscura::ssao {

// eq. 18: cos of the visibility cone's half-angle for cosine-weighted AO, sqrt(1 - A).
float visibilityConeCos(float ao);
// eq. 26: cos of the specular cone's half-angle, 0.01^(r^2 / 2) = exp(-2.30259 r^2).
float specularConeCos(float roughness);
// Solid angle of the intersection of two spherical caps of half-angles alpha1, alpha2 (radians, [0, pi])
// whose axes are beta apart ([0, pi]) (Tovchigrechko and Vakser 2001; Mazonka 2012).
float capIntersectionSolidAngle(float alpha1, float alpha2, float beta);
// eq. 19: Omega_i / Omega_s for the cone about w_r, beta = angle(b, w_r).
float specularOcclusionCone(float alphaV, float beta, float roughness);

constexpr int kSpecularTableSize = 32;  // samples per dimension (32^4 and 32^3 entries)

class SpecularOcclusionTable {
public:
    // 4-D S(alpha_v, beta, roughness, theta_o) of eq. 21, and the 3-D variant with b = n (beta = theta_o).
    static const SpecularOcclusionTable& fourD();
    static const SpecularOcclusionTable& threeD();

    // Multilinear lookup. alpha_v in [0, pi/2], beta in [0, pi], roughness in [0, 1], theta_o in [0, pi/2].
    // The 3-D table ignores beta (it is theta_o there).
    float lookup(float alphaV, float beta, float roughness, float thetaO) const;
    // The value stored at grid node (i, j, k, l) (alpha_v, beta, roughness, theta_o); j ignored in 3-D.
    float node(int i, int j, int k, int l) const;
    static float alphaVAt(int i);
    static float betaAt(int j);
    static float roughnessAt(int k);
    static float thetaOAt(int l);
    bool isFourD() const { return fourD_; }

private:
    explicit SpecularOcclusionTable(bool fourD);
    bool fourD_;
    std::vector<float> values_;
};

enum class SpecularOcclusionMode { Lut4, Lut3, Cone };

// S for one shading point; all vectors unit, in one space; view points from the surface to the eye.
float specularOcclusion(SpecularOcclusionMode mode, float ao, Vec3 bentNormal, Vec3 normal, Vec3 view,
                        float roughness);

// Per pixel from a G-buffer, its AO and bent normals (view space), with one roughness for every pixel
// (the G-buffer carries none). Sky pixels get 1. Throws obscura::Error on a size mismatch or a roughness
// outside [0, 1].
Image computeSpecularOcclusion(const GBuffer& gbuffer, const Image& ao, const Image& bentNormal,
                               SpecularOcclusionMode mode, float roughness);

} // namespace obscura::ssao
