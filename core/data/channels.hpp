// The channels one accumulation pass (accumulate.hpp) can fill: a plain set of flags, so that the tracer can
// be told what its caller will shade without depending on the pass itself.
#pragma once

namespace sonarsim {

struct Channels {
    bool image = false;         ///< the ideal image L_EN [dB]
    bool sensor_inputs = false; ///< SensorInputs (fine azimuth columns, mean elevations)
    bool ground_truth = false;  ///< GroundTruth
    bool path_orders = false;   ///< echo per path order (multipath metadata)
    bool strongest = false;     ///< per (bin, beam) the strongest contribution (hovering, drawing its path)
    bool any() const { return image || sensor_inputs || ground_truth || path_orders || strongest; }
};

} // namespace sonarsim
