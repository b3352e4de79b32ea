#ifndef talus_structure_axial_law_h
#define talus_structure_axial_law_h

#include <string>

namespace Talus
{
  namespace Structure
  {
    /** Strain measure of the axial law of cables, sliding cables and bars. */
    enum class StrainMeasure
    {
      /** eps = (l^2 - L^2)/(2 L^2), PK2 stress, N = A S l/L. */
      green_lagrange,
      /** N = EA (l - l0)/l0 with the unstretched length l0 (steel ropes
       * as barrier engineers specify them). */
      engineering
    };

    /** The values of a 'strain measure' entry, for Patterns::Selection. */
    inline const std::string strain_measure_names =
      "engineering|Green-Lagrange";

    /** The measure named @p name (one of strain_measure_names). */
    StrainMeasure
    strain_measure_from_string(const std::string &name);

    /** The name of @p measure, as in strain_measure_names. */
    std::string
    to_string(const StrainMeasure measure);


    /**
     * Elastic axial law of a cable or bar: the axial force N as a function
     * of the stretch lambda = l/L, l the current and L the reference
     * length (of the mesh), with the pre-stress sigma_0, the axial stress
     * at the reference length (N(1) = A sigma_0 for both measures):
     *
     * Green-Lagrange (PK2 stress S):
     *   eps = (lambda^2 - 1)/2,  S = E eps + sigma_0,  N = A S lambda,
     *   dN/dlambda = EA (3 lambda^2 - 1)/2 + A sigma_0,
     *   W/L = A (E eps^2/2 + sigma_0 eps)  (zero at l = L).
     *
     * Engineering strain on the unstretched length l0 = L lambda_0,
     * lambda_0 = 1/(1 + sigma_0/E) (sigma_0 > -E):
     *   N = EA (l - l0)/l0 = EA (lambda/lambda_0 - 1),
     *   dN/dl = EA/l0,  W = EA (l - l0)^2/(2 l0)  (zero when slack).
     *
     * The two differ at second order in the strain: at the engineering
     * strain e = l/l0 - 1 (sigma_0 = 0) N_GL/N_eng = (1 + e)(1 + e/2),
     * +3.0 % at e = 2 % (doc/theory.md, "Axial law of cables").
     * Tension only elements treat N < 0 as slack; N = 0 (l = l0) is taut.
     */
    struct AxialLaw
    {
      StrainMeasure measure        = StrainMeasure::green_lagrange;
      double        youngs_modulus = 0.; ///< E [Pa]
      double        area           = 0.; ///< A [m^2]
      double        prestress      = 0.; ///< sigma_0 [Pa]

      /** l0/L = 1/(1 + sigma_0/E) (engineering); throws if sigma_0 <= -E
       * (no positive unstretched length). */
      double
      unstretched_ratio() const;

      /** N(lambda) [N]; negative in compression (slack for a cable). */
      double
      force(const double lambda) const;

      /** dN/dlambda [N]. */
      double
      stiffness(const double lambda) const;

      /** Strain energy per reference length W/L at stretch lambda, taut
       * (N >= 0) [J/m]. */
      double
      energy(const double lambda) const;

      /** Strain energy per reference length of a slack cable (N < 0): the
       * minimum of energy() [J/m]. */
      double
      slack_energy() const;

      /** The stretch lambda >= lambda(N = 0) at which N(lambda) = @p N >=
       * 0 [-]. */
      double
      stretch(const double N) const;
    };
  } // namespace Structure
} // namespace Talus

#endif
