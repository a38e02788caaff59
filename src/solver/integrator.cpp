#include "src/solver/integrator.hpp"

#include "src/solver/cvode_integrator.hpp"
#include "src/solver/implicit_euler_integrator.hpp"

namespace panoptic {

std::unique_ptr<Integrator> make_integrator(DiskModel& model, double t0,
                                            std::span<const double> y0,
                                            IntegratorOptions options) {
  if (options.method == IntegrationMethod::implicit_euler)
    return std::make_unique<ImplicitEulerIntegrator>(model, t0, y0, std::move(options));
  return std::make_unique<CvodeIntegrator>(model, t0, y0, std::move(options));
}

}  // namespace panoptic
