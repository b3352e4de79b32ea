#ifndef talus_app_coupled_simulation_h
#define talus_app_coupled_simulation_h

#include <talus/boundaries/boundary_particles.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <string>

namespace Talus
{
  /**
   * The coupled application (`set problem = coupled`): the MPM of the file
   * (every subsection of `set problem = mpm`), the structure model of
   * subsection `Structure` and the partitioned coupling of subsection
   * `Coupling` (Coupling::GaussSeidelCoupling over MPM::MPMProblem and
   * Structure::StructureProblem, interface Coupling::StructureInterface).
   * The loop takes coupled steps of the time control's size, halves the
   * step of both fields when the interface or a field does not converge,
   * writes `coupling.csv` (per step: coupling iterations, interface
   * residual, relaxation, Newton iterations of both fields, interface
   * force and work, energies of both fields) and the points and the
   * structure for visualization, and checks subsection
   * `Coupling/Verification` (interface force, mean iterations, energy
   * balance, conservation, and the probe: the mass-weighted mean
   * displacement of the material points that start in a box). With
   * `Coupling/initial structure state = unloaded` the structure starts
   * under its pre-stress only and takes its own loads in the first step
   * together with the MPM (one body split into two fields, as
   * tests/coupled/split_cantilever); `loaded` (default) solves its
   * equilibrium under them before the coupling.
   *
   * Checkpoints (subsection `Checkpoint`, doc/checkpoint.md) hold both
   * fields, the coupling's history and the time loop's records
   * (Coupling::GaussSeidelCoupling::save_checkpoint(), the archive
   * `time_loop` of coupled_checkpoint.cc); a resumed run continues as the
   * uninterrupted one.
   */
  template <int dim>
  class CoupledSimulation
  {
  public:
    explicit CoupledSimulation(const MPI_Comm communicator);

    /** Every parameter of a coupled run. */
    static void
    declare_parameters(
      dealii::ParameterHandler &prm,
      const unsigned int        n_boundaries =
        Boundaries::BoundaryParticles<dim>::default_boundary_slots);

    /** Declare subsection `Coupling` (with `Interface` and
     * `Verification`) alone, e.g. for --print-parameters. */
    static void
    declare_coupling_parameters(dealii::ParameterHandler &prm);

    /** Continue from the checkpoint (or the newest in the directory)
     * @p path instead of starting at t = 0 (`talus --resume`;
     * doc/checkpoint.md). */
    void
    set_resume(const std::string &path)
    {
      resume_from = path;
    }

    /** Run the file's coupled problem; returns the exit code. */
    int
    run(dealii::ParameterHandler &prm);

  private:
    MPI_Comm    communicator;
    std::string resume_from;
  };
} // namespace Talus

#endif
