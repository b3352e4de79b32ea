#ifndef talus_app_structure_simulation_h
#define talus_app_structure_simulation_h

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace Talus
{
  /**
   * The structure-only application (`set problem = structure`): builds one
   * of the structural models of subsection `Structure` (von Mises truss,
   * elastic catenary, Hencky circular membrane, pre-stressed square
   * membrane, sliding ring, cable with brake), solves it with the static
   * solver (load or displacement stepping, Newton with line search),
   * writes VTU files and a CSV of the load steps, and compares the result
   * with the model's closed form (exit code 3 if a tolerance is missed),
   * optionally on a sequence of refined meshes with a convergence table.
   */
  namespace StructureSimulation
  {
    /** Declare subsection `Structure` and everything in it. */
    void
    declare_parameters(dealii::ParameterHandler &prm);

    /** Run the file (already checked to ask for problem = structure). */
    int
    run_parameter_file(const std::string &filename);
  } // namespace StructureSimulation
} // namespace Talus

#endif
