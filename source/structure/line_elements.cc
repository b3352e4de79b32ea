#include <talus/structure/line_elements.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace Talus
{
  namespace Structure
  {
    LineResponse::LineResponse()
      : f(6)
      , K(6, 6)
    {}


    void
    LineElement::assemble_axial(const dealii::Tensor<1, 3> &e,
                                const double                l,
                                const double                N,
                                const double                dN_dl,
                                LineResponse               &response)
    {
      for (unsigned int i = 0; i < 3; ++i)
        {
          response.f[i]     = -N * e[i];
          response.f[i + 3] = N * e[i];
        }
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          {
            const double k =
              dN_dl * e[i] * e[j] + N / l * ((i == j ? 1. : 0.) - e[i] * e[j]);
            response.K(i, j)         = k;
            response.K(i + 3, j + 3) = k;
            response.K(i, j + 3)     = -k;
            response.K(i + 3, j)     = -k;
          }
    }


    void
    LineElement::assemble_slack(const double k_reg, LineResponse &response)
    {
      response.f     = 0.;
      response.K     = 0.;
      response.force = 0.;
      response.slack = true;
      for (unsigned int i = 0; i < 3; ++i)
        {
          response.K(i, i)         = k_reg;
          response.K(i + 3, i + 3) = k_reg;
          response.K(i, i + 3)     = -k_reg;
          response.K(i + 3, i)     = -k_reg;
        }
    }


    void
    LineElement::add_transverse(const double                k_reg,
                                const dealii::Tensor<1, 3> &e,
                                LineResponse               &response)
    {
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          {
            const double k = k_reg * ((i == j ? 1. : 0.) - e[i] * e[j]);
            response.K(i, j) += k;
            response.K(i + 3, j + 3) += k;
            response.K(i, j + 3) -= k;
            response.K(i + 3, j) -= k;
          }
    }


    namespace
    {
      /** l, e and L of an element; throws on a zero length. */
      void
      kinematics(const dealii::Tensor<1, 3> &X0,
                 const dealii::Tensor<1, 3> &X1,
                 const dealii::Tensor<1, 3> &x0,
                 const dealii::Tensor<1, 3> &x1,
                 double                     &L,
                 double                     &l,
                 dealii::Tensor<1, 3>       &e)
      {
        L = (X1 - X0).norm();
        l = (x1 - x0).norm();
        if (!(L > 0.) || !(l > 0.))
          throw std::runtime_error(
            "A line element has zero length (coincident nodes).");
        e = (x1 - x0) / l;
      }
    } // namespace


    std::string
    Truss::name() const
    {
      return "truss";
    }


    double
    Truss::mass_per_length() const
    {
      return density * area;
    }


    double
    LineElement::dissipated_energy(const dealii::Tensor<1, 3> &,
                                   const dealii::Tensor<1, 3> &,
                                   const LineState &) const
    {
      return 0.;
    }


    double
    Truss::dissipated_energy(const dealii::Tensor<1, 3> &X0,
                             const dealii::Tensor<1, 3> &X1,
                             const LineState            &state) const
    {
      const double alpha = state.accumulated;
      return area * (X1 - X0).norm() *
             (yield_stress * alpha + 0.5 * hardening * alpha * alpha);
    }


    double
    Brake::dissipated_energy(const dealii::Tensor<1, 3> &,
                             const dealii::Tensor<1, 3> &,
                             const LineState &state) const
    {
      return state.accumulated;
    }


    void
    Truss::compute(const dealii::Tensor<1, 3> &X0,
                   const dealii::Tensor<1, 3> &X1,
                   const dealii::Tensor<1, 3> &x0,
                   const dealii::Tensor<1, 3> &x1,
                   const LineState            &old_state,
                   LineResponse               &r) const
    {
      double               L, l;
      dealii::Tensor<1, 3> e;
      kinematics(X0, X1, x0, x1, L, l, e);
      const bool engineering = strain_measure == StrainMeasure::engineering;
      // Engineering: the unstretched length l0 and eps = (l - l0)/l0, so
      // that S = E eps = sigma_0 at l = L.
      const double l0 =
        engineering ?
          L * AxialLaw{strain_measure, youngs_modulus, area, prestress}
                .unstretched_ratio() :
          L;
      const double eps =
        engineering ? (l - l0) / l0 : (l * l - L * L) / (2. * L * L);
      r.strain = eps;
      r.slack  = false;
      r.state  = old_state;

      double S = youngs_modulus * (eps - old_state.plastic) +
                 (engineering ? 0. : prestress);
      double Et = youngs_modulus;
      if (yield_stress > 0.)
        {
          const double phi =
            std::abs(S) - (yield_stress + hardening * old_state.accumulated);
          if (phi > 0.)
            {
              const double dgamma = phi / (youngs_modulus + hardening);
              const double sign   = S > 0. ? 1. : -1.;
              r.state.plastic += dgamma * sign;
              r.state.accumulated += dgamma;
              S -= youngs_modulus * dgamma * sign;
              Et = youngs_modulus * hardening / (youngs_modulus + hardening);
            }
        }
      const double eps_e = eps - r.state.plastic;
      if (engineering)
        {
          r.force  = area * S;
          r.energy = 0.5 * area * l0 * youngs_modulus * eps_e * eps_e;
          assemble_axial(e, l, r.force, Et * area / l0, r);
          return;
        }
      const double N     = area * S * l / L;
      const double dN_dl = Et * area * l * l / (L * L * L) + area * S / L;
      r.force            = N;
      r.energy =
        area * L * (0.5 * youngs_modulus * eps_e * eps_e + prestress * eps_e);
      assemble_axial(e, l, N, dN_dl, r);
    }


    std::string
    Cable::name() const
    {
      return "cable";
    }


    double
    Cable::mass_per_length() const
    {
      return density * area;
    }


    void
    Cable::compute(const dealii::Tensor<1, 3> &X0,
                   const dealii::Tensor<1, 3> &X1,
                   const dealii::Tensor<1, 3> &x0,
                   const dealii::Tensor<1, 3> &x1,
                   const LineState            &old_state,
                   LineResponse               &r) const
    {
      double               L, l;
      dealii::Tensor<1, 3> e;
      kinematics(X0, X1, x0, x1, L, l, e);
      r.state = old_state;
      if (strain_measure == StrainMeasure::engineering)
        {
          const AxialLaw law    = this->law();
          const double   lambda = l / L;
          const double   N      = law.force(lambda);
          r.strain              = lambda / law.unstretched_ratio() - 1.;
          if (N < 0.)
            {
              assemble_slack(slack_stiffness_ratio * youngs_modulus * area / L,
                             r);
              r.energy = L * law.slack_energy();
              return;
            }
          r.slack  = false;
          r.force  = N;
          r.energy = L * law.energy(lambda);
          assemble_axial(e, l, N, law.stiffness(lambda) / L, r);
          if (N == 0.)
            add_transverse(slack_stiffness_ratio * youngs_modulus * area / L,
                           e,
                           r);
          return;
        }
      const double eps = (l * l - L * L) / (2. * L * L);
      r.strain         = eps;
      const double S   = youngs_modulus * eps + prestress;
      if (S < 0.)
        {
          assemble_slack(slack_stiffness_ratio * youngs_modulus * area / L, r);
          r.energy = -area * L * prestress * prestress / (2. * youngs_modulus);
          return;
        }
      r.slack        = false;
      const double N = area * S * l / L;
      const double dN_dl =
        youngs_modulus * area * l * l / (L * L * L) + area * S / L;
      r.force = N;
      r.energy =
        area * L * (0.5 * youngs_modulus * eps * eps + prestress * eps);
      assemble_axial(e, l, N, dN_dl, r);
      if (N == 0.)
        add_transverse(slack_stiffness_ratio * youngs_modulus * area / L, e, r);
    }


    AxialLaw
    Cable::law() const
    {
      return AxialLaw{strain_measure, youngs_modulus, area, prestress};
    }


    std::string
    Brake::name() const
    {
      return "brake";
    }


    double
    Brake::mass_per_length() const
    {
      return mass;
    }


    void
    Brake::compute(const dealii::Tensor<1, 3> &X0,
                   const dealii::Tensor<1, 3> &X1,
                   const dealii::Tensor<1, 3> &x0,
                   const dealii::Tensor<1, 3> &x1,
                   const LineState            &old_state,
                   LineResponse               &r) const
    {
      double               L, l;
      dealii::Tensor<1, 3> e;
      kinematics(X0, X1, x0, x1, L, l, e);
      const double d = l - L;
      r.strain       = (l * l - L * L) / (2. * L * L);
      r.state        = old_state;
      const double s = old_state.plastic;
      if (d - s < 0.)
        {
          assemble_slack(slack_stiffness_ratio * stiffness, r);
          r.energy = 0.;
          return;
        }
      r.slack          = false;
      double     N     = stiffness * (d - s);
      double     dN_dl = stiffness;
      const bool blocked =
        stroke_limit > 0. && s >= stroke_limit * (1. - 1e-14);
      if (!blocked)
        {
          const double phi = N - (activation_force + hardening * s);
          if (phi > 0.)
            {
              double dgamma = phi / (stiffness + hardening);
              if (stroke_limit > 0. && s + dgamma >= stroke_limit)
                // The stroke ends within this increment: the brake blocks.
                dgamma = stroke_limit - s;
              else
                dN_dl = stiffness * hardening / (stiffness + hardening);
              const double s_new = s + dgamma;
              r.state.plastic    = s_new;
              r.state.accumulated += activation_force * dgamma +
                                     0.5 * hardening * (s_new * s_new - s * s);
              N = stiffness * (d - s_new);
            }
        }
      r.force  = N;
      r.energy = 0.5 * N * N / stiffness;
      assemble_axial(e, l, N, dN_dl, r);
    }
  } // namespace Structure
} // namespace Talus
