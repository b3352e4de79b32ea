#ifndef talus_coupling_interface_transfer_h
#define talus_coupling_interface_transfer_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/vector.h>

#include <deal.II/dofs/dof_handler.h>

#include <vector>

namespace Talus
{
  namespace Coupling
  {
    /**
     * The transfer between a structure's interface mesh and the MPM's
     * boundary particles (founding paper, section 4; deal.II step-70): the
     * particles are points of the interface mesh (a membrane's
     * Triangulation<2,3>, a string's Triangulation<1,2>, a solid's boundary),
     * and each keeps the cell of the mesh it lies in and its reference
     * coordinates xi_p there, found once by reinit(), so that no transfer
     * searches.
     *
     * With the shape functions N_i of the mesh's finite element (a
     * FESystem of spacedim FE_Q components),
     *
     *   displacement (consistent):   u_p = sum_i N_i(xi_p) U_i
     *   force (conservative):        F_i = sum_p N_i(xi_p) f_p
     *
     * the force map is the transpose of the displacement map, so the
     * summed force (sum_i F_i = sum_p f_p, the N_i of each component sum to
     * one) and the interface work (U . F = sum_p u_p . f_p) are the same on
     * both sides to round-off. The shape values are those of deal.II's
     * FEValues at a quadrature made of the point's reference coordinates
     * (FEPointEvaluation is dim == spacedim only in deal.II 9.4).
     *
     * The point list and the force vector are local: on several MPI ranks
     * each rank passes its own particles and the caller sums F over the
     * ranks (one MPI_Allreduce of the interface vector).
     */
    template <int dim, int spacedim>
    class InterfaceTransfer
    {
    public:
      /**
       * Locate @p points (positions in the reference configuration of the
       * interface mesh of @p dof_handler, e.g. the boundary particles'
       * reference positions) in the mesh and store the shape values and
       * degrees of freedom of each. A point farther than @p tolerance
       * (relative to its cell's diameter) from the mesh is an error that
       * names it.
       */
      void
      reinit(const dealii::DoFHandler<dim, spacedim>    &dof_handler,
             const std::vector<dealii::Point<spacedim>> &points,
             const double                                tolerance = 1e-10);

      /** Number of points. */
      unsigned int
      n_points() const
      {
        return point_dofs.size();
      }

      /**
       * The displacement of every point for the nodal displacement @p U
       * (indexed by the DoFs of the dof handler) [m].
       */
      std::vector<dealii::Tensor<1, spacedim>>
      interpolate(const dealii::Vector<double> &U) const;

      /**
       * Add the nodal forces of the point forces @p f (one per point, in the
       * order of reinit()) to @p F [N].
       */
      void
      distribute(const std::vector<dealii::Tensor<1, spacedim>> &f,
                 dealii::Vector<double>                         &F) const;

      /** Cell (active cell index) of point @p p. */
      unsigned int
      cell_index(const unsigned int p) const
      {
        return point_cells[p];
      }

      /** Reference coordinates of point @p p in its cell. */
      const dealii::Point<dim> &
      reference_point(const unsigned int p) const
      {
        return reference_points[p];
      }

    private:
      std::vector<unsigned int>       point_cells;
      std::vector<dealii::Point<dim>> reference_points;
      /** DoFs of the point's cell. */
      std::vector<std::vector<dealii::types::global_dof_index>> point_dofs;
      /** Per point and cell DoF: its component and N_i(xi_p). */
      std::vector<std::vector<std::pair<unsigned int, double>>> point_shapes;
    };
  } // namespace Coupling
} // namespace Talus

#endif
