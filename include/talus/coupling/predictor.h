#ifndef talus_coupling_predictor_h
#define talus_coupling_predictor_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/vector.h>

#include <deque>
#include <string>

namespace boost
{
  namespace archive
  {
    class binary_oarchive;
    class binary_iarchive;
  } // namespace archive
} // namespace boost

namespace Talus
{
  namespace Coupling
  {
    /**
     * Predictor of the interface displacement at the start of a coupled
     * step: the first iterate x_0 of the window at t_{n+1}, extrapolated in
     * time from the last converged windows (preCICE 2's
     * `extrapolation-order`, Küttler & Wall 2008 §4). With the converged
     * values x_n, x_{n−1}, x_{n−2} at t_n, t_{n−1}, t_{n−2}, the Lagrange
     * polynomial through the last p + 1 of them is evaluated at t_{n+1}:
     * - none (p = 0): x_0 = x_n;
     * - linear (p = 1): x_0 = x_n + (x_n − x_{n−1}) Δt_{n+1}/Δt_n
     *   (2 x_n − x_{n−1} for a constant step);
     * - quadratic (p = 2): 3 x_n − 3 x_{n−1} + x_{n−2} for a constant step.
     * Variable steps (rejections, an adaptive step) are handled by the
     * Lagrange weights. With fewer stored windows the order drops to what
     * they allow (record the initial state with add_converged(t_0, x_0)).
     *
     * Parameter (subsection `Coupling`): `predictor = none|linear|quadratic`.
     */
    class InterfacePredictor
    {
    public:
      enum class Order
      {
        none      = 0,
        linear    = 1,
        quadratic = 2
      };

      explicit InterfacePredictor(const Order order = Order::none);

      /** Declare the entry in the current subsection. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Parse from the current subsection. */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /** Record the converged interface displacement @p x at time @p t
       * (t must grow). */
      void
      add_converged(const double t, const dealii::Vector<double> &x);

      /** The predicted interface displacement at @p t_next > the last
       * recorded time. Requires at least one recorded value. */
      dealii::Vector<double>
      predict(const double t_next) const;

      /** Forget the history (e.g. the interface changed). */
      void
      clear();

      Order
      order() const;

      /** Number of recorded windows (at most order + 1 are kept). */
      unsigned int
      n_stored() const;

      /** Write the recorded windows into a checkpoint archive. */
      void
      save(boost::archive::binary_oarchive &archive) const;

      /** Read the recorded windows of save(). */
      void
      load(boost::archive::binary_iarchive &archive);

    private:
      Order                              extrapolation_order;
      std::deque<double>                 times;  // newest first
      std::deque<dealii::Vector<double>> values; // newest first
    };
  } // namespace Coupling
} // namespace Talus

#endif
