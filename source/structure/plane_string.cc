#include <talus/structure/plane_string.h>

#include <stdexcept>

namespace Talus
{
  namespace Structure
  {
    LineMesh &
    PlaneString::add_to(Structure                                &structure,
                        const std::string                        &name,
                        const std::shared_ptr<const LineElement> &element)
    {
      if (triangulation.n_active_cells() == 0)
        throw std::runtime_error("The plane string <" + name +
                                 "> has no cells.");
      std::vector<dealii::Point<3>> vertices;
      for (const auto &x : triangulation.get_vertices())
        vertices.emplace_back(x[0], x[1], 0.);
      std::vector<dealii::CellData<1>> cells;
      for (const auto &cell : triangulation.active_cell_iterators())
        {
          dealii::CellData<1> c;
          c.vertices = {cell->vertex_index(0), cell->vertex_index(1)};
          cells.push_back(c);
        }
      mesh       = structure.line_meshes.size();
      auto &line = structure.add_line_mesh(name, element);
      // Vertex numbers are kept: vertex v of the 2D mesh is vertex v here.
      line.triangulation.create_triangulation(vertices,
                                              cells,
                                              dealii::SubCellData());
      return line;
    }


    void
    PlaneString::setup(Structure &structure)
    {
      vertex_nodes = structure.line_vertex_nodes(mesh);
      for (const unsigned int n : vertex_nodes)
        if (n != dealii::numbers::invalid_unsigned_int)
          structure.prescribe(n, 2);
    }


    unsigned int
    PlaneString::node(const unsigned int v) const
    {
      AssertIndexRange(v, vertex_nodes.size());
      return vertex_nodes[v];
    }


    void
    PlaneString::fix(Structure &structure, const unsigned int v) const
    {
      for (unsigned int c = 0; c < 2; ++c)
        structure.prescribe(node(v), c);
    }


    dealii::Point<2>
    PlaneString::current_position(const Structure              &structure,
                                  const dealii::Vector<double> &u,
                                  const unsigned int            v) const
    {
      const dealii::Point<3> x = structure.node_current_position(u, node(v));
      return dealii::Point<2>(x[0], x[1]);
    }


    void
    PlaneString::set_external_force(Structure                  &structure,
                                    const unsigned int          v,
                                    const dealii::Tensor<1, 2> &F) const
    {
      structure.set_external_force(node(v),
                                   dealii::Tensor<1, 3>({F[0], F[1], 0.}));
    }


    dealii::Tensor<1, 2>
    PlaneString::reaction(const Structure   &structure,
                          const unsigned int v) const
    {
      const dealii::Tensor<1, 3> R = structure.reaction(node(v));
      return dealii::Tensor<1, 2>({R[0], R[1]});
    }
  } // namespace Structure
} // namespace Talus
