#include <talus/coupling/predictor.h>

#include <deal.II/base/exceptions.h>

namespace Talus
{
  namespace Coupling
  {
    InterfacePredictor::InterfacePredictor(const Order order)
      : extrapolation_order(order)
    {}


    void
    InterfacePredictor::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.declare_entry(
        "predictor",
        "linear",
        dealii::Patterns::Selection("none|linear|quadratic"),
        "First interface displacement of a step, extrapolated in time from "
        "the converged displacements of the last steps: none (the last "
        "one), linear (last two) or quadratic (last three).");
    }


    void
    InterfacePredictor::parse_parameters(dealii::ParameterHandler &prm)
    {
      const std::string p = prm.get("predictor");
      extrapolation_order = (p == "none"   ? Order::none :
                             p == "linear" ? Order::linear :
                                             Order::quadratic);
      clear();
    }


    void
    InterfacePredictor::add_converged(const double                  t,
                                      const dealii::Vector<double> &x)
    {
      AssertThrow(times.empty() || t > times.front(),
                  dealii::ExcMessage("The times of the converged interface "
                                     "displacements must grow."));
      times.push_front(t);
      values.push_front(x);
      const unsigned int keep =
        static_cast<unsigned int>(extrapolation_order) + 1;
      while (times.size() > keep)
        {
          times.pop_back();
          values.pop_back();
        }
    }


    dealii::Vector<double>
    InterfacePredictor::predict(const double t_next) const
    {
      AssertThrow(!values.empty(),
                  dealii::ExcMessage(
                    "No converged interface displacement yet."));
      // Lagrange polynomial through the stored points, evaluated at t_next.
      const unsigned int     n = values.size();
      dealii::Vector<double> x(values.front().size());
      for (unsigned int i = 0; i < n; ++i)
        {
          double weight = 1.;
          for (unsigned int j = 0; j < n; ++j)
            if (j != i)
              weight *= (t_next - times[j]) / (times[i] - times[j]);
          x.add(weight, values[i]);
        }
      return x;
    }


    void
    InterfacePredictor::clear()
    {
      times.clear();
      values.clear();
    }


    InterfacePredictor::Order
    InterfacePredictor::order() const
    {
      return extrapolation_order;
    }


    unsigned int
    InterfacePredictor::n_stored() const
    {
      return values.size();
    }
  } // namespace Coupling
} // namespace Talus
