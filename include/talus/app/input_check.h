#ifndef talus_app_input_check_h
#define talus_app_input_check_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace Talus
{
  /**
   * A subsection or entry name as deal.II's JSON and XML export writes it
   * (every character that is not a letter or digit as _XX, hex) turned
   * back into the name.
   */
  std::string
  demangle_parameter_name(const std::string &mangled);

  /**
   * Checks of an input file that need nothing but the file: they run before
   * a simulation allocates anything (main.cc calls check_input_file() first)
   * and are all that `talus --check <file>` does. Each failure throws
   * ExcInvalidInput naming the file, the line, the parameter and what is
   * allowed (deal.II's own parse errors, an unknown entry or a value that
   * does not match its pattern, are thrown as deal.II exceptions).
   */
  namespace InputCheck
  {
    /**
     * The file must exist and contain at least one `set` (or `include`)
     * statement: an empty or comments-only file would silently run the
     * built-in defaults.
     */
    void
    require_statements(const std::string &filename);

    /**
     * The first pass over an input file: only `problem` ("mpm" or
     * "structure", returned) and `dimension` (set in @p dimension).
     */
    std::string
    problem_and_dimension(const std::string &filename, unsigned int &dimension);

    /**
     * Declare every parameter of the file's problem in @p prm and parse the
     * file, as a run does: first `problem` and `dimension` alone, then the
     * full declarations (Simulation<dim> for `problem = mpm`,
     * StructureSimulation for `problem = structure`). Returns the problem
     * ("mpm" or "structure") and sets @p dimension.
     */
    std::string
    parse(const std::string        &filename,
          dealii::ParameterHandler &prm,
          unsigned int             &dimension);

    /**
     * Every number in every value of @p prm (the tokens of lists, vectors,
     * function constants and expressions) must be finite: `nan`, `inf` and
     * literals beyond the range of a double (1e400) are rejected.
     */
    void
    require_finite_numbers(const dealii::ParameterHandler &prm);

    /**
     * Reject an MPM run whose estimated memory per rank on the finest level
     * of its convergence study exceeds the limit of subsection `Memory`
     * (MPM::MemoryEstimate, without the internal variables of the model).
     */
    void
    require_memory(const dealii::ParameterHandler &prm,
                   const unsigned int              dimension,
                   const MPI_Comm                  communicator);
  } // namespace InputCheck

  /**
   * All of the checks above for @p filename (the same on every rank, so
   * every rank throws). Returns a one-line summary for `talus --check`.
   */
  std::string
  check_input_file(const std::string &filename, const MPI_Comm communicator);

  /**
   * `talus --check FILE...`: check_input_file() for each file. Prints on
   * rank 0, per file, `talus --check: <FILE> is valid (...)` (stdout) or
   * `talus --check: <FILE> is not valid:` and the error a run would print
   * (stderr). Returns 0 if every file is valid, 1 otherwise (2 without a
   * file).
   */
  int
  check_input_files(const std::vector<std::string> &filenames,
                    const MPI_Comm                  communicator);
} // namespace Talus

#endif
