// Unit conversions shared by the physics, the shading and the sampler.
#pragma once

namespace sonarsim {

/// ln(10) / 10: a level x [dB] is exp(x * kLn10Over10) in power; a natural log y is y / kLn10Over10 dB.
inline constexpr double kLn10Over10 = 0.23025850929940458;

} // namespace sonarsim
