#include <talus/base/input.h>
#include <talus/structure/barrier_builder.h>

#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <cmath>

namespace Talus
{
  namespace Structure
  {
    using namespace dealii;

    void
    BarrierBuilder::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Barrier");
      prm.declare_entry("number of fields",
                        "3",
                        Patterns::Integer(1, 20),
                        "Fields of net between the posts (posts: fields + "
                        "1) [-].");
      prm.declare_entry("field width",
                        "5",
                        Patterns::Double(),
                        "Distance between neighbouring posts [m], > 0.");
      prm.declare_entry("height",
                        "3.5",
                        Patterns::Double(),
                        "Height of the post heads above the bases [m], > 0.");
      prm.declare_entry("post inclination",
                        "10",
                        Patterns::Double(0, 45),
                        "Downslope inclination of the posts from the "
                        "vertical [degrees], 0 to 45.");
      prm.declare_entry("anchor distance",
                        "6",
                        Patterns::Double(),
                        "Upslope distance of the retaining rope anchors "
                        "from the post bases [m], > 0.");
      prm.declare_entry("anchor spread",
                        "1.5",
                        Patterns::Double(0),
                        "The two retaining ropes of a post end at x_post "
                        "+- this value [m].");
      prm.declare_entry("end anchor offset",
                        "4",
                        Patterns::Double(),
                        "Ground anchors of the top and bottom support "
                        "cables: this far beyond the outer posts [m], > 0 "
                        "(bottom cable: in line with the bases; top cable: "
                        "vertically below the line of the post heads).");
      prm.declare_entry("field load",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 3, 3),
                        "Total force on the net of the loaded field (x, y, "
                        "z; the flow pushes towards -y), shared equally by "
                        "the net nodes of that field and scaled by the load "
                        "factor [N].");
      prm.declare_entry("loaded field",
                        "1",
                        Patterns::Integer(0),
                        "Index of the field that carries the field load, "
                        "0 to number of fields - 1 (1: the middle field of "
                        "three) [-].");
      prm.declare_entry("lateral anchor offset",
                        "4",
                        Patterns::Double(),
                        "Ground anchors of the lateral ropes of the outer "
                        "post heads: this far beyond the outer posts [m], "
                        "> 0.");
      prm.declare_entry("lateral anchor downslope",
                        "2",
                        Patterns::Double(0),
                        "Ground anchors of the lateral ropes: this far "
                        "downslope of the post heads [m], >= 0.");
      prm.declare_entry("net cells per field",
                        "4",
                        Patterns::Integer(1, 256),
                        "Membrane cells along the barrier per field [-].");
      prm.declare_entry("net cells over height",
                        "4",
                        Patterns::Integer(1, 256),
                        "Membrane cells between bottom and top [-].");
      prm.declare_entry("brake length",
                        "0.5",
                        Patterns::Double(),
                        "Length of the brake element at the anchor end of "
                        "each retaining rope [m], > 0.");
      const auto member = [&](const std::string &name,
                              const std::string &E,
                              const std::string &A,
                              const std::string &prestress) {
        prm.enter_subsection(name);
        prm.declare_entry("Young's modulus",
                          E,
                          Patterns::Double(),
                          "E [Pa], > 0.");
        prm.declare_entry("cross-section area",
                          A,
                          Patterns::Double(),
                          "A [m^2], > 0.");
        prm.declare_entry("density",
                          "7850",
                          Patterns::Double(),
                          "Density [kg/m^3], >= 0.");
        if (!prestress.empty())
          prm.declare_entry("prestress",
                            prestress,
                            Patterns::Double(),
                            "Pre-stress at the reference length (PK2 with "
                            "Green-Lagrange; engineering: unstretched "
                            "length L/(1 + prestress/E)) [Pa], >= 0.");
        prm.declare_entry("strain measure",
                          "Green-Lagrange",
                          Patterns::Selection(strain_measure_names),
                          "Axial law: 'Green-Lagrange' (N = A (E (l^2 - "
                          "L^2)/(2 L^2) + sigma_0) l/L) or 'engineering' "
                          "(N = EA (l - l0)/l0, l0 the unstretched length) "
                          "[-].");
        prm.leave_subsection();
      };
      member("Posts", "2.1e11", "3e-3", "");
      member("Support cables", "1.2e11", "2e-4", "1e8");
      member("Retaining ropes", "1.2e11", "2e-4", "1e7");
      member("Lateral ropes", "1.2e11", "2e-4", "");
      prm.leave_subsection();
    }


    void
    BarrierBuilder::parse_parameters(ParameterHandler  &prm,
                                     const std::string &path)
    {
      prm.enter_subsection("Barrier");
      n_fields              = prm.get_integer("number of fields");
      field_width           = get_positive(prm, path, "field width");
      height                = get_positive(prm, path, "height");
      inclination           = prm.get_double("post inclination");
      anchor_distance       = get_positive(prm, path, "anchor distance");
      anchor_spread         = prm.get_double("anchor spread");
      end_anchor_offset     = get_positive(prm, path, "end anchor offset");
      lateral_anchor_offset = get_positive(prm, path, "lateral anchor offset");
      lateral_anchor_downslope =
        get_non_negative(prm, path, "lateral anchor downslope");
      cells_per_field = prm.get_integer("net cells per field");
      {
        const auto v = Utilities::string_to_double(
          Utilities::split_string_list(prm.get("field load")));
        field_load   = Tensor<1, 3>({v[0], v[1], v[2]});
        loaded_field = prm.get_integer("loaded field");
        if (loaded_field >= n_fields)
          InputFile::reject(path,
                            "loaded field",
                            prm.get("loaded field"),
                            "it must be smaller than the number of fields (" +
                              std::to_string(n_fields) + ")");
      }
      cells_over_height = prm.get_integer("net cells over height");
      brake_length      = get_positive(prm, path, "brake length");
      const auto member = [&](const std::string &name,
                              double            &E,
                              double            &A,
                              double            &rho,
                              double            *prestress,
                              StrainMeasure     &measure) {
        prm.enter_subsection(name);
        measure = strain_measure_from_string(prm.get("strain measure"));
        E       = get_positive(prm, path + "/" + name, "Young's modulus");
        A       = get_positive(prm, path + "/" + name, "cross-section area");
        rho     = get_non_negative(prm, path + "/" + name, "density");
        if (prestress != nullptr)
          *prestress = get_non_negative(prm, path + "/" + name, "prestress");
        prm.leave_subsection();
      };
      member("Posts", post_E, post_A, post_density, nullptr, post_strain);
      member("Support cables",
             cable_E,
             cable_A,
             cable_density,
             &cable_prestress,
             cable_strain);
      member("Retaining ropes",
             rope_E,
             rope_A,
             rope_density,
             &rope_prestress,
             rope_strain);
      member("Lateral ropes",
             lateral_E,
             lateral_A,
             lateral_density,
             nullptr,
             lateral_strain);
      prm.leave_subsection();
    }


    namespace
    {
      void
      polyline(Triangulation<1, 3> &tria, const std::vector<Point<3>> &x)
      {
        std::vector<CellData<1>> cells(x.size() - 1);
        for (unsigned int i = 0; i + 1 < x.size(); ++i)
          cells[i].vertices = {i, i + 1};
        tria.create_triangulation(x, cells, SubCellData());
      }

      /** Disconnected segments (a, b) in one mesh. */
      void
      segments(Triangulation<1, 3>                              &tria,
               const std::vector<std::pair<Point<3>, Point<3>>> &ab)
      {
        std::vector<Point<3>>    x;
        std::vector<CellData<1>> cells(ab.size());
        for (unsigned int i = 0; i < ab.size(); ++i)
          {
            x.push_back(ab[i].first);
            x.push_back(ab[i].second);
            cells[i].vertices = {2 * i, 2 * i + 1};
          }
        tria.create_triangulation(x, cells, SubCellData());
      }
    } // namespace


    Point<3>
    BarrierBuilder::net_point(const double x, const double s) const
    {
      const double theta = inclination * numbers::PI / 180.;
      return Point<3>(x, -s * std::sin(theta), s * std::cos(theta));
    }


    double
    BarrierBuilder::post_length() const
    {
      return height / std::cos(inclination * numbers::PI / 180.);
    }


    std::vector<unsigned int>
    BarrierBuilder::field_nodes(const Structure   &s,
                                const unsigned int field) const
    {
      const double              Hs  = post_length();
      const double              tol = 1e-8 * (n_fields * field_width + Hs);
      std::vector<unsigned int> nodes;
      for (unsigned int k = 0; k <= cells_per_field; ++k)
        for (unsigned int j = 0; j <= cells_over_height; ++j)
          {
            const unsigned int n =
              s.find_node(net_point((field + double(k) / cells_per_field) *
                                      field_width,
                                    j * Hs / cells_over_height),
                          tol);
            AssertThrow(n != numbers::invalid_unsigned_int,
                        ExcMessage("internal: net node not found"));
            nodes.push_back(n);
          }
      return nodes;
    }


    void
    BarrierBuilder::build(Structure &s)
    {
      const double       theta = inclination * numbers::PI / 180.;
      const double       L     = n_fields * field_width;
      const double       Hs    = post_length();
      const unsigned int nx    = n_fields * cells_per_field;
      const unsigned int nz    = cells_over_height;

      // Posts: one Truss each, base to head.
      auto post            = std::make_shared<Truss>();
      post->youngs_modulus = post_E;
      post->area           = post_A;
      post->density        = post_density;
      post->strain_measure = post_strain;
      std::vector<std::pair<Point<3>, Point<3>>> post_segments;
      for (unsigned int i = 0; i <= n_fields; ++i)
        post_segments.emplace_back(net_point(i * field_width, 0.),
                                   net_point(i * field_width, Hs));
      post_meshes = {static_cast<unsigned int>(s.line_meshes.size())};
      segments(s.add_line_mesh("posts", post).triangulation, post_segments);

      // Sliding support cables.
      auto cable            = std::make_shared<SlidingCable>();
      cable->youngs_modulus = cable_E;
      cable->area           = cable_A;
      cable->prestress      = cable_prestress;
      cable->density        = cable_density;
      cable->strain_measure = cable_strain;
      const double   y_head = -Hs * std::sin(theta);
      const Point<3> anchor_left(-end_anchor_offset, 0, 0),
        anchor_right(L + end_anchor_offset, 0, 0),
        top_left(-end_anchor_offset, y_head, 0),
        top_right(L + end_anchor_offset, y_head, 0);
      std::vector<Point<3>> top = {top_left}, bottom = {anchor_left};
      for (unsigned int k = 0; k <= nx; ++k)
        {
          top.push_back(net_point(k * L / nx, Hs));
          bottom.push_back(net_point(k * L / nx, 0.));
        }
      top.push_back(top_right);
      bottom.push_back(anchor_right);
      std::vector<Point<3>> edge_left, edge_right;
      for (unsigned int j = 0; j <= nz; ++j)
        {
          edge_left.push_back(net_point(0., j * Hs / nz));
          edge_right.push_back(net_point(L, j * Hs / nz));
        }
      support_cable_meshes.clear();
      for (const auto &[name, points] :
           std::vector<std::pair<std::string, std::vector<Point<3>>>>{
             {"top_cable", top},
             {"bottom_cable", bottom},
             {"edge_cable_left", edge_left},
             {"edge_cable_right", edge_right}})
        {
          support_cable_meshes.push_back(s.line_meshes.size());
          polyline(s.add_sliding_cable(name, cable).triangulation, points);
        }

      // Retaining ropes with a brake at the anchor end.
      auto rope               = std::make_shared<Cable>();
      rope->youngs_modulus    = rope_E;
      rope->area              = rope_A;
      rope->prestress         = rope_prestress;
      rope->density           = rope_density;
      rope->strain_measure    = rope_strain;
      auto brake              = std::make_shared<Brake>();
      brake->stiffness        = brake_k;
      brake->activation_force = brake_Fa;
      brake->hardening        = brake_H;
      brake->stroke_limit     = brake_smax;
      std::vector<std::pair<Point<3>, Point<3>>> ropes, brakes;
      std::vector<Point<3>>                      anchors = {anchor_left,
                                                            anchor_right,
                                                            top_left,
                                                            top_right};

      // Lateral ropes of the outer post heads, pre-stressed so that their
      // force along x balances the inward pull on the outer heads in the
      // initial geometry.
      {
        const double   T       = cable_A * cable_prestress;
        const Point<3> head0   = net_point(0., Hs);
        const double   cos_phi = end_anchor_offset / head0.distance(top_left);
        const Point<3> lateral_left(-lateral_anchor_offset,
                                    y_head - lateral_anchor_downslope,
                                    0.),
          lateral_right(L + lateral_anchor_offset,
                        y_head - lateral_anchor_downslope,
                        0.);
        const double cos_lateral =
          lateral_anchor_offset / head0.distance(lateral_left);
        // Inward pull on the outer head: the top cable, T (1 - cos phi),
        // and half of the net's pre-stress along x carried by the edge
        // cable between base and head, n_x H_s / 2.
        const double n_x = net.material.prestress[0] * net.material.thickness;
        lateral_prestress =
          (T * (1. - cos_phi) + 0.5 * n_x * Hs) / (cos_lateral * lateral_A);
        auto lateral            = std::make_shared<Cable>();
        lateral->youngs_modulus = lateral_E;
        lateral->area           = lateral_A;
        lateral->prestress      = lateral_prestress;
        lateral->density        = lateral_density;
        lateral->strain_measure = lateral_strain;
        lateral_rope_meshes = {static_cast<unsigned int>(s.line_meshes.size())};
        segments(s.add_line_mesh("lateral_ropes", lateral).triangulation,
                 {{lateral_left, head0}, {lateral_right, net_point(L, Hs)}});
        anchors.push_back(lateral_left);
        anchors.push_back(lateral_right);
      }
      for (unsigned int i = 0; i <= n_fields; ++i)
        for (const double side : {-1., 1.})
          {
            const Point<3>     head = net_point(i * field_width, Hs);
            const Point<3>     anchor(i * field_width + side * anchor_spread,
                                  anchor_distance,
                                  0.);
            const Tensor<1, 3> d = (head - anchor) / head.distance(anchor);
            const Point<3>     p = anchor + brake_length * d;
            brakes.emplace_back(anchor, p);
            ropes.emplace_back(p, head);
            anchors.push_back(anchor);
          }
      rope_meshes = {static_cast<unsigned int>(s.line_meshes.size())};
      segments(s.add_line_mesh("retaining_ropes", rope).triangulation, ropes);
      brake_meshes = {static_cast<unsigned int>(s.line_meshes.size())};
      segments(s.add_line_mesh("brakes", brake).triangulation, brakes);

      // The net.
      {
        auto &mesh = s.add_membrane("net", std::make_shared<Membrane>(net));
        Triangulation<2> flat;
        GridGenerator::subdivided_hyper_rectangle(flat,
                                                  {nx, nz},
                                                  Point<2>(0., 0.),
                                                  Point<2>(L, Hs));
        GridGenerator::flatten_triangulation(flat, mesh.triangulation);
        GridTools::transform(
          [&](const Point<3> &p) { return net_point(p[0], p[1]); },
          mesh.triangulation);
      }

      s.setup_dofs();
      supports.clear();
      post_heads.clear();
      const double tol = 1e-8 * (L + Hs);
      for (unsigned int i = 0; i <= n_fields; ++i)
        {
          supports.push_back(s.find_node(net_point(i * field_width, 0.), tol));
          post_heads.push_back(
            s.find_node(net_point(i * field_width, Hs), tol));
        }
      anchor_points = anchors;
      for (const auto &a : anchors)
        supports.push_back(s.find_node(a, tol));
      for (const unsigned int n : supports)
        {
          AssertThrow(n != numbers::invalid_unsigned_int,
                      ExcMessage("internal: barrier support not found"));
          for (unsigned int c = 0; c < 3; ++c)
            s.prescribe(n, c);
        }
      if (field_load.norm() > 0.)
        {
          const auto nodes = field_nodes(s, loaded_field);
          for (const unsigned int n : nodes)
            s.add_point_load(n, field_load / double(nodes.size()));
        }
    }
  } // namespace Structure
} // namespace Talus
