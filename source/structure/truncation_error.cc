#include <talus/structure/truncation_error.h>

#include <cmath>

namespace Talus
{
  namespace Structure
  {
    double
    newmark_beta(const StructureProblem &structure)
    {
      const double alpha = structure.get_dynamic_solver().alpha;
      return 0.25 * (1. - alpha) * (1. - alpha);
    }


    TruncationErrorNorms
    truncation_error_norms(const StructureProblem       &structure,
                           const dealii::Vector<double> &u_n,
                           const double                  dt)
    {
      TruncationErrorNorms norms;
      if (!structure.is_dynamic())
        return norms;
      const auto  &solver      = structure.get_dynamic_solver();
      const auto  &S           = structure.get_structure();
      const auto  &M           = S.lumped_mass();
      const auto  &constraints = S.get_constraints();
      const auto  &u           = structure.displacement();
      const double beta        = newmark_beta(structure);
      double       sums[3]     = {0., 0., 0.};
      for (unsigned int i = 0; i < u.size(); ++i)
        {
          if (!(M[i] > 0.) || constraints.is_constrained(i))
            continue;
          const double du = u[i] - u_n[i];
          const double an = solver.acceleration[i];
          const double a  = (du - dt * solver.velocity[i]) / (beta * dt * dt) -
                           (0.5 - beta) / beta * an;
          sums[0] += M[i] * (a - an) * (a - an);
          sums[1] += M[i] * du * du;
          sums[2] += M[i];
        }
      if (sums[2] > 0.)
        {
          norms.acceleration_change = std::sqrt(sums[0] / sums[2]);
          norms.increment           = std::sqrt(sums[1] / sums[2]);
          norms.mass                = sums[2];
        }
      return norms;
    }
  } // namespace Structure
} // namespace Talus
