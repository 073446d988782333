#pragma once
/// Modified Phong BRDF (Lambert is the ks = 0 case) with importance sampling.
///
///   f(ωo, ωi) = kd/π + ks (n+2)/(2π) cos^n α,   α = angle(reflect(ωo, N), ωi)
///
/// Sampling picks the diffuse lobe with probability pd = avg(kd)/(avg(kd)+avg(ks)) and the Phong lobe
/// otherwise; the returned weight f·cosθ/pdf uses the mixture pdf, so it is unbiased whichever lobe
/// produced the direction. The pure lobes use their closed-form weights (kd, and
/// ks (n+2)/(n+1) cosθ) so that no 0/0 appears when cos^n α underflows at huge exponents.

#include "core/util/warp.h"
#include "core/scene/scene.h"

namespace rrf {

struct Brdf {
    Vec3 kd{0.f}, ks{0.f};
    float n = 1.f;
    float pDiffuse = 1.f;  ///< probability of sampling the diffuse lobe

    Brdf() = default;
    explicit Brdf(const Material& m) : kd(m.kd), ks(m.type == Material::Type::Phong ? m.ks : Vec3(0.f)), n(m.exponent) {
        const float d = kd.sum(), s = ks.sum();
        pDiffuse = (d + s) > 0.f ? d / (d + s) : 1.f;
    }

    /// f(ωo, ωi) in the local frame (z = shading normal, both directions pointing away).
    Vec3 eval(const Vec3& wo, const Vec3& wi) const {
        if (wi.z <= 0.f || wo.z <= 0.f) return Vec3(0.f);
        Vec3 f = kd * kInvPi;
        if (!ks.isZero()) {
            const float cosAlpha = dot(reflect(wo, Vec3(0, 0, 1)), wi);
            f += ks * ((n + 2.f) * kInv2Pi * powCos(cosAlpha, n));
        }
        return f;
    }

    /// Mixture pdf (solid angle) of sample().
    float pdf(const Vec3& wo, const Vec3& wi) const {
        if (wi.z <= 0.f || wo.z <= 0.f) return 0.f;
        float p = pDiffuse * cosineHemispherePdf(wi.z);
        if (pDiffuse < 1.f) p += (1.f - pDiffuse) * phongLobePdf(dot(reflect(wo, Vec3(0, 0, 1)), wi), n);
        return p;
    }

    /// Samples ωi; returns false for directions below the surface. `weight` = f·cosθi / pdf.
    /// `u` picks the lobe (reused after rescaling), (u1, u2) warp the direction.
    bool sample(const Vec3& wo, float uLobe, float u1, float u2, Vec3& wi, Vec3& weight) const {
        if (wo.z <= 0.f) return false;
        if (uLobe < pDiffuse) {
            wi = sampleCosineHemisphere(u1, u2);
            if (wi.z <= 0.f) return false;
            if (pDiffuse >= 1.f) {  // Lambert: f cosθ / pdf = kd exactly
                weight = kd;
                return true;
            }
        } else {
            const Frame lobe(reflect(wo, Vec3(0, 0, 1)));
            wi = lobe.toWorld(samplePhongLobe(u1, u2, n));
            if (wi.z <= 0.f) return false;
            if (pDiffuse <= 0.f) {  // pure Phong: ks (n+2)/(n+1) cosθ, no cos^n α ratio
                weight = ks * ((n + 2.f) / (n + 1.f) * wi.z);
                return true;
            }
        }
        const float p = pdf(wo, wi);
        if (!(p > 0.f)) return false;
        weight = eval(wo, wi) * (wi.z / p);
        return true;
    }
};

}  // namespace rrf
