#ifndef talus_structure_plane_string_h
#define talus_structure_plane_string_h

#include <talus/structure/structure.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/grid/tria.h>

#include <memory>
#include <string>
#include <vector>

namespace Talus
{
  namespace Structure
  {
    /**
     * A string (cables or trusses along a line) of a two-dimensional
     * problem, e.g. a barrier in a plane-strain MPM simulation: its mesh is
     * a Triangulation<1,2> in the (x, y) plane of the 2D problem. The
     * Structure solves it as a line mesh in its plane z = 0, vertex (x, y)
     * at (x, y, 0), with u_z = 0 prescribed at every node, so that all
     * elements, loads, solvers and supports of the 3D structure apply; this
     * class maps between the two: 2D positions, displacements, forces and
     * reactions by vertex of the Triangulation<1,2>. Gravity of the 2D
     * problem (0, -g) is Structure::gravity (0, -g, 0).
     *
     * Use: fill triangulation, add_to() before Structure::setup_dofs(),
     * setup() after it (before Structure::setup_system()).
     */
    class PlaneString
    {
    public:
      /** The 2D mesh (vertices in the plane of the 2D problem) [m]. */
      dealii::Triangulation<1, 2> triangulation;

      /** Add the string to @p structure as line mesh @p name (a copy of
       * the triangulation in the plane z = 0) made of @p element. */
      LineMesh &
      add_to(Structure                                &structure,
             const std::string                        &name,
             const std::shared_ptr<const LineElement> &element);

      /** After Structure::setup_dofs(): map the vertices to nodes and
       * prescribe u_z = 0 at every node of the string. */
      void
      setup(Structure &structure);

      /** Node of the structure at vertex @p v of the triangulation. */
      unsigned int
      node(const unsigned int v) const;

      /** Fix both displacement components of vertex @p v (a support). */
      void
      fix(Structure &structure, const unsigned int v) const;

      /** Current position of vertex @p v for displacement @p u [m]. */
      dealii::Point<2>
      current_position(const Structure              &structure,
                       const dealii::Vector<double> &u,
                       const unsigned int            v) const;

      /** Set the external force on vertex @p v [N] (the coupling). */
      void
      set_external_force(Structure                  &structure,
                         const unsigned int          v,
                         const dealii::Tensor<1, 2> &F) const;

      /** In-plane force of the string on the support at vertex @p v after
       * the last assembly [N] (Structure::reaction). */
      dealii::Tensor<1, 2>
      reaction(const Structure &structure, const unsigned int v) const;

    private:
      unsigned int              mesh = 0;
      std::vector<unsigned int> vertex_nodes;
    };
  } // namespace Structure
} // namespace Talus

#endif
