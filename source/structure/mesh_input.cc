#include <talus/base/input.h>
#include <talus/structure/mesh_input.h>

#include <deal.II/grid/grid_in.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace Talus
{
  namespace Structure
  {
    namespace
    {
      /** Dimension of a Gmsh element type (-1: unknown). */
      int
      gmsh_element_dimension(const int type)
      {
        switch (type)
          {
            case 15:
              return 0;
            case 1:
            case 8:
            case 26:
            case 27:
            case 28:
              return 1;
            case 2:
            case 3:
            case 9:
            case 10:
            case 16:
            case 20:
            case 21:
            case 22:
            case 23:
            case 24:
            case 25:
              return 2;
            case 4:
            case 5:
            case 6:
            case 7:
            case 11:
            case 12:
            case 13:
            case 14:
            case 17:
            case 18:
            case 19:
            case 29:
            case 30:
            case 31:
            case 92:
            case 93:
              return 3;
            default:
              return -1;
          }
      }


      std::string
      trimmed(const std::string &s)
      {
        const auto b = s.find_first_not_of(" \t\r");
        if (b == std::string::npos)
          return "";
        const auto e = s.find_last_not_of(" \t\r");
        return s.substr(b, e - b + 1);
      }


      /** Next line as a string stream (throws at the end of the file). */
      std::istringstream
      next_line(std::istream &in)
      {
        std::string line;
        if (!std::getline(in, line))
          throw std::runtime_error("unexpected end of file");
        return std::istringstream(line);
      }
    } // namespace


    std::vector<GmshNode>
    find_unconnected_gmsh_nodes(const std::string &filename,
                                const unsigned int cell_dim)
    {
      std::ifstream in(filename);
      if (!in)
        return {};
      std::map<std::size_t, dealii::Point<3>> nodes;
      std::set<std::size_t>                   used;
      double                                  version        = 0.;
      bool                                    found_elements = false;
      try
        {
          std::string line;
          while (std::getline(in, line))
            {
              line = trimmed(line);
              if (line == "$MeshFormat")
                next_line(in) >> version;
              else if (line == "$Nodes" && version >= 4.)
                {
                  std::size_t n_blocks = 0;
                  next_line(in) >> n_blocks;
                  for (std::size_t b = 0; b < n_blocks; ++b)
                    {
                      int entity_dim = 0, entity_tag = 0, parametric = 0;
                      std::size_t n = 0;
                      next_line(in) >> entity_dim >> entity_tag >> parametric >>
                        n;
                      std::vector<std::size_t> tags(n);
                      for (std::size_t i = 0; i < n; ++i)
                        next_line(in) >> tags[i];
                      for (std::size_t i = 0; i < n; ++i)
                        {
                          dealii::Point<3> x;
                          next_line(in) >> x[0] >> x[1] >> x[2];
                          nodes[tags[i]] = x;
                        }
                    }
                }
              else if (line == "$Nodes" && version >= 2.)
                {
                  std::size_t n = 0;
                  next_line(in) >> n;
                  for (std::size_t i = 0; i < n; ++i)
                    {
                      std::size_t      tag = 0;
                      dealii::Point<3> x;
                      next_line(in) >> tag >> x[0] >> x[1] >> x[2];
                      nodes[tag] = x;
                    }
                }
              else if (line == "$Elements" && version >= 4.)
                {
                  found_elements       = true;
                  std::size_t n_blocks = 0;
                  next_line(in) >> n_blocks;
                  for (std::size_t b = 0; b < n_blocks; ++b)
                    {
                      int         entity_dim = 0, entity_tag = 0, type = 0;
                      std::size_t n = 0;
                      next_line(in) >> entity_dim >> entity_tag >> type >> n;
                      for (std::size_t i = 0; i < n; ++i)
                        {
                          auto        element = next_line(in);
                          std::size_t tag = 0, node = 0;
                          element >> tag;
                          if (entity_dim == static_cast<int>(cell_dim))
                            while (element >> node)
                              used.insert(node);
                        }
                    }
                }
              else if (line == "$Elements" && version >= 2.)
                {
                  found_elements = true;
                  std::size_t n  = 0;
                  next_line(in) >> n;
                  for (std::size_t i = 0; i < n; ++i)
                    {
                      auto         element = next_line(in);
                      std::size_t  tag = 0, node = 0;
                      int          type   = 0;
                      unsigned int n_tags = 0;
                      element >> tag >> type >> n_tags;
                      for (unsigned int t = 0; t < n_tags; ++t)
                        element >> node;
                      if (gmsh_element_dimension(type) ==
                          static_cast<int>(cell_dim))
                        while (element >> node)
                          used.insert(node);
                    }
                }
            }
        }
      catch (const std::exception &)
        {
          return {};
        }
      if (version < 2. || !found_elements)
        return {};
      std::vector<GmshNode> result;
      for (const auto &[tag, x] : nodes)
        if (used.find(tag) == used.end())
          result.push_back({tag, x});
      return result;
    }


    template <int dim, int spacedim>
    void
    read_gmsh_mesh(dealii::Triangulation<dim, spacedim> &tria,
                   const std::string                    &filename,
                   const std::string                    &subsection,
                   const std::string                    &entry,
                   const std::string                    &what)
    {
      std::ifstream in(filename);
      if (!in)
        InputFile::reject(subsection,
                          entry,
                          filename,
                          "the file cannot be opened");
      const auto unconnected = find_unconnected_gmsh_nodes(filename, dim);
      if (!unconnected.empty())
        {
          std::ostringstream msg;
          msg << "every node of the mesh must belong to one of its " << what
              << ", and " << unconnected.size() << " node"
              << (unconnected.size() > 1 ? "s do" : " does")
              << " not: an unconnected node (Gmsh node " << unconnected[0].tag
              << " at (" << unconnected[0].position[0] << ", "
              << unconnected[0].position[1] << ", "
              << unconnected[0].position[2]
              << ")) would carry no stiffness and be dropped; connect it "
                 "to a cell or delete it from the file";
          InputFile::reject(subsection, entry, filename, msg.str());
        }
      dealii::GridIn<dim, spacedim> grid_in;
      grid_in.attach_triangulation(tria);
      try
        {
          grid_in.read(in, dealii::GridIn<dim, spacedim>::Format::msh);
        }
      catch (const std::exception &)
        {
          InputFile::reject(subsection,
                            entry,
                            filename,
                            "it is not a readable Gmsh (.msh) file of " + what);
        }
      if (tria.n_active_cells() == 0)
        InputFile::reject(subsection,
                          entry,
                          filename,
                          "it is not a readable Gmsh (.msh) file of " + what +
                            " (it has no cells)");
    }


    template void
    read_gmsh_mesh(dealii::Triangulation<1, 3> &,
                   const std::string &,
                   const std::string &,
                   const std::string &,
                   const std::string &);
    template void
    read_gmsh_mesh(dealii::Triangulation<2, 3> &,
                   const std::string &,
                   const std::string &,
                   const std::string &,
                   const std::string &);
    template void
    read_gmsh_mesh(dealii::Triangulation<3, 3> &,
                   const std::string &,
                   const std::string &,
                   const std::string &,
                   const std::string &);
  } // namespace Structure
} // namespace Talus
