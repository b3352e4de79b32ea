#ifndef talus_materials_exceptions_h
#define talus_materials_exceptions_h

#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace Talus
{
  namespace Materials
  {
    /**
     * Thrown by a constitutive model that is evaluated at a deformation
     * gradient with @f$J = \det\mathbf F \le 0@f$ (or a non-finite
     * @f$J@f$): the material point would be turned inside out, and the
     * stress of a finite-strain model is undefined there; or with
     * @f$J > 0@f$ but numerically singular (a non-positive eigenvalue of
     * the elastic left Cauchy-Green tensor).
     *
     * This is not an input error: the solver catches it and rejects the
     * step (for instance by cutting the time step) instead of continuing
     * with NaN stresses.
     */
    class ExcInvertedMaterialPoint : public std::runtime_error
    {
    public:
      /**
       * @param model_name  name of the model that was evaluated
       * @param det_F  the offending Jacobian @f$J = \det\mathbf F@f$
       */
      ExcInvertedMaterialPoint(const std::string &model_name,
                               const double       det_F)
        : std::runtime_error(make_message(model_name, det_F))
        , det_F_value(det_F)
      {}

      /** The Jacobian @f$\det\mathbf F@f$ that was rejected. */
      double
      det_F() const
      {
        return det_F_value;
      }

    private:
      static std::string
      make_message(const std::string &model_name, const double det_F)
      {
        std::ostringstream msg;
        if (det_F > 0. && det_F < std::numeric_limits<double>::infinity())
          msg << "Degenerate material point: the " << model_name
              << " model was evaluated at a deformation gradient with det F "
                 "= "
              << det_F
              << " that is numerically singular (its elastic left "
                 "Cauchy-Green tensor has a non-positive eigenvalue: the "
                 "point is stretched in one direction and crushed in "
                 "another).";
        else
          msg << "Inverted material point: the " << model_name
              << " model was evaluated at a deformation gradient with det F "
                 "= "
              << det_F << ", but it needs 0 < det F < infinity.";
        return msg.str();
      }

      double det_F_value;
    };


    /**
     * Thrown when the local (material point) return mapping of an
     * elastoplastic model fails: the local Newton iteration did not
     * converge, produced non-finite values, or no admissible return was
     * found. Like ExcInvertedMaterialPoint this is not an input error: the
     * solver catches it (as an std::exception) and rejects the step, e.g.
     * by cutting the time step.
     */
    class ExcReturnMappingFailed : public std::runtime_error
    {
    public:
      explicit ExcReturnMappingFailed(const std::string &message)
        : std::runtime_error(message)
      {}
    };
  } // namespace Materials
} // namespace Talus

#endif
