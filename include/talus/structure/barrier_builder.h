#ifndef talus_structure_barrier_builder_h
#define talus_structure_barrier_builder_h

#include <talus/structure/structure.h>

#include <deal.II/base/parameter_handler.h>

#include <vector>

namespace Talus
{
  namespace Structure
  {
    /**
     * Builds the standard flexible barrier of the founding paper (Singer et
     * al., section 5, Fig. 5) from parameters: n fields of equal width
     * between n + 1 posts, a net (Membrane on Triangulation<2,3>) spanned
     * between the post bases and heads, sliding support cables along the
     * top and bottom edge of the net (through every net edge node, the
     * post heads/bases, anchored in the ground beyond the outer posts) and
     * along the two outer edges (base to head of the outer posts), two
     * retaining ropes per post head to upslope ground anchors, each with a
     * brake in series near its anchor, and one lateral rope from each
     * outer post head outwards and downslope to a ground anchor.
     *
     * Why the lateral ropes and where the anchors are: a post hinged at
     * its base with two retaining ropes is a statically determinate
     * tripod; the ropes stay in tension only if the other forces on the
     * head point down or downslope. Inner heads carry the pull of the net
     * (down), but the top support cable bends over the outer heads down to
     * its end anchors and pulls each outer head inwards with T (1 - cos
     * phi) (T its tension, phi the angle of its end segment below the
     * horizontal), which the retaining ropes cannot take without going
     * slack. The lateral rope takes it: its pre-stress is chosen so that
     * its force along x balances T (1 - cos phi) + n_x H_s / 2 (n_x the
     * net's pre-stress along x, half of which the edge cable carries to
     * the head) in the initial geometry,
     * and its anchor lies downslope of the head so that it pulls the outer
     * posts downslope. The end anchors of the top cable lie at ground level
     * vertically below the line of the heads (y = y_head), so that the top
     * cable pulls the outer heads neither up- nor downslope. The
     * tripod being determinate, the force of the retaining ropes follows
     * from statics whatever their pre-stress (a pre-stress only shortens
     * them by sigma_0/E, and the head moves by that much); a small one
     * (default 10 MPa) keeps the rope-brake node stable during the first
     * stage of the form finding, when the heads are held.
     *
     * Coordinates: x along the barrier, y upslope (the flow comes from +y),
     * z up. Post i stands on the hinge (x_i, 0, 0) and leans downslope by
     * the inclination angle: head (x_i, -H tan(theta), H). Posts are
     * single Truss elements (hinged at the base: a support without
     * moments). The net plane contains the posts; its vertices on the post
     * lines at the base and head coincide with the post nodes and are tied
     * to them, as are cable nodes with net edge nodes (shackles). All
     * ground anchors and post bases are fixed.
     */
    class BarrierBuilder
    {
    public:
      unsigned int n_fields          = 3;
      double       field_width       = 5.;  ///< [m]
      double       height            = 3.5; ///< post height H [m]
      double       inclination       = 10.; ///< theta [degrees]
      double       anchor_distance   = 6.;  ///< upslope, from the bases [m]
      double       anchor_spread     = 1.5; ///< +- along x [m]
      double       end_anchor_offset = 4.;  ///< beyond the outer posts [m]
      unsigned int cells_per_field   = 4;   ///< net cells along x per field
      unsigned int cells_over_height = 4;   ///< net cells along the posts
      double       brake_length      = 0.5; ///< brake element length [m]
      /** Total force on the net of field loaded_field, shared equally by
       * its nodes, scaled by the load factor [N]. */
      dealii::Tensor<1, 3> field_load;
      unsigned int         loaded_field = 1;  ///< 0-based field index [-]
      double lateral_anchor_offset      = 4.; ///< beyond the outer posts [m]
      double lateral_anchor_downslope   = 2.; ///< downslope of the heads [m]

      double post_E = 2.1e11, post_A = 3e-3, post_density = 7850.;
      double cable_E = 1.2e11, cable_A = 2e-4, cable_prestress = 1e8,
             cable_density = 7850.;
      double rope_E = 1.2e11, rope_A = 2e-4, rope_prestress = 1e7,
             rope_density = 7850.;
      double lateral_E = 1.2e11, lateral_A = 2e-4, lateral_density = 7850.;
      /** Axial laws of the posts, support cables, retaining and lateral
       * ropes (AxialLaw). */
      StrainMeasure post_strain    = StrainMeasure::green_lagrange,
                    cable_strain   = StrainMeasure::green_lagrange,
                    rope_strain    = StrainMeasure::green_lagrange,
                    lateral_strain = StrainMeasure::green_lagrange;
      /** Pre-stress of the lateral ropes computed by build() [Pa]. */
      double   lateral_prestress = 0.;
      double   brake_k = 1e6, brake_Fa = 5e4, brake_H = 0., brake_smax = 1.;
      Membrane net;

      /** Subsection "Barrier" (everything but the net material, which is
       * subsection "Membrane" of the caller). */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Parse subsection "Barrier"; @p path is its path for messages. */
      void
      parse_parameters(dealii::ParameterHandler &prm, const std::string &path);

      /** Add all meshes, call setup_dofs(), fix the supports, add the
       * field load. */
      void
      build(Structure &structure);

      /** Nodes of the post bases and ground anchors (the supports). */
      std::vector<unsigned int> supports;
      /** Nodes of the post heads. */
      std::vector<unsigned int> post_heads;
      /** Ground anchors (supports) in the order: bottom cable ends, top
       * cable ends, lateral rope anchors, retaining rope anchors. */
      std::vector<dealii::Point<3>> anchor_points;
      /** Indices of the meshes by role in Structure::line_meshes. */
      std::vector<unsigned int> post_meshes, support_cable_meshes, rope_meshes,
        brake_meshes, lateral_rope_meshes;

      /** Position of the point at distance @p s along the post direction
       * above (x, 0, 0) in the net plane [m]. */
      dealii::Point<3>
      net_point(const double x, const double s) const;

      /** Length of the posts (base to head) [m]. */
      double
      post_length() const;

      /** Nodes of the net in field @p field (0-based, including its
       * edges on the post lines, top and bottom). */
      std::vector<unsigned int>
      field_nodes(const Structure &structure, const unsigned int field) const;
    };
  } // namespace Structure
} // namespace Talus

#endif
