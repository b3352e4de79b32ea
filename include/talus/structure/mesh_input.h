#ifndef talus_structure_mesh_input_h
#define talus_structure_mesh_input_h

#include <deal.II/base/point.h>

#include <deal.II/grid/tria.h>

#include <cstddef>
#include <string>
#include <vector>

namespace Talus
{
  namespace Structure
  {
    /** A node of a Gmsh file and its position [m]. */
    struct GmshNode
    {
      std::size_t      tag = 0;
      dealii::Point<3> position;
    };


    /**
     * The nodes of the Gmsh file @p filename (ASCII, format 2.x or 4.x)
     * that no element of dimension @p cell_dim references: vertices that
     * belong to no cell of the structural mesh read from it (lines for
     * cables and trusses, quadrilaterals for membranes, hexahedra for
     * solids). deal.II's GridIn drops such vertices silently; for a
     * structure they are a modelling error (a node meant to carry a support
     * or a tie that is connected to nothing). Nodes referenced only by
     * point elements (Gmsh type 15) or by elements of another dimension
     * count as unconnected. Returns an empty list for a file it cannot
     * parse (GridIn then reports it) or of the legacy format 1.
     */
    std::vector<GmshNode>
    find_unconnected_gmsh_nodes(const std::string &filename,
                                const unsigned int cell_dim);


    /**
     * Read the Gmsh file @p filename into @p tria. Every failure is an
     * ExcInvalidInput that names parameter @p entry of subsection
     * @p subsection (where the file name was given): the file cannot be
     * opened, it is not a Gmsh file of cells of dimension @p dim
     * (@p what describes them, e.g. "line elements"), or it has a node
     * that no cell uses (find_unconnected_gmsh_nodes(): the message gives
     * the node's tag and position).
     */
    template <int dim, int spacedim>
    void
    read_gmsh_mesh(dealii::Triangulation<dim, spacedim> &tria,
                   const std::string                    &filename,
                   const std::string                    &subsection,
                   const std::string                    &entry,
                   const std::string                    &what);
  } // namespace Structure
} // namespace Talus

#endif
