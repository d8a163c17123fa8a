// The rays of one bake sample and their evaluation, shared by traceSamples and the raw-Embree throughput
// check, so both trace exactly the same rays and the check can time the bake's own path beside bare Embree.
#pragma once

#include "obscura/bake.h"
#include "obscura/sampling.h"
#include "obscura/trace.h"
#include "obscura/trace_stream.h"

#include <algorithm>
#include <vector>

namespace obscura::bake::detail {

struct SampleFrame {
    Vec3 origin, t, b, n;
    CosineHemisphereSet::Shift shift;
};

class SampleTracer {
public:
    SampleTracer(const trace::Tracer& tracer, const BakeSettings& settings);

    struct Scratch {
        std::vector<Vec3> directions;
        std::vector<float> t;
        std::vector<std::uint8_t> back;
    };
    Scratch scratch() const;

    SampleFrame frame(const SampleSet& samples, std::size_t s) const;
    // Ray i of a sample, in packet order.
    Vec3 direction(const SampleFrame& f, std::size_t i) const {
        const Vec3 l = directions_.direction(order_[i], f.shift);
        return f.t * l.x + f.b * l.y + f.n * l.z;
    }
    // Traces sample s; writes one value per channel and returns how many rays hit a back face.
    int trace(const SampleSet& samples, std::size_t s, Scratch& scratch, float* values) const;

    int rays() const { return settings_.rays; }
    float tfar() const { return tfar_; }

private:
    const trace::Tracer& tracer_;
    BakeSettings settings_;
    CosineHemisphereSet directions_;
    std::vector<int> order_;
    trace::HitStream stream_;
    float a_[2] = {0, 0}, d_[2] = {0, 0};
    float tfar_ = 0;
};

} // namespace obscura::bake::detail
