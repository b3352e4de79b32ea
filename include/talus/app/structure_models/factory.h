#ifndef talus_app_structure_models_factory_h
#define talus_app_structure_models_factory_h

#include <talus/app/structure_models/model.h>

#include <memory>

namespace Talus
{
  namespace StructureModels
  {
    /**
     * The model that subsection Structure asks for (entry 'model'; a file
     * name of a line or membrane mesh otherwise).
     */
    std::unique_ptr<Model>
    create_model(const Parameters &p);

    /** @name The models, one per file of source/app/structure_models/
     * @{ */
    std::unique_ptr<Model>
    create_vibrating_string(const Parameters &p);

    std::unique_ptr<Model>
    create_sheared_membrane(const Parameters &p);

    std::unique_ptr<Model>
    create_stretched_membrane(const Parameters &p);

    std::unique_ptr<Model>
    create_plastic_bar(const Parameters &p);

    std::unique_ptr<Model>
    create_capstan(const Parameters &p);

    std::unique_ptr<Model>
    create_barrier(const Parameters &p);

    std::unique_ptr<Model>
    create_solid_model(const Parameters &p);

    std::unique_ptr<Model>
    create_cantilever(const Parameters &p);

    std::unique_ptr<Model>
    create_hanging_block(const Parameters &p);

    std::unique_ptr<Model>
    create_axial_bar(const Parameters &p);

    std::unique_ptr<Model>
    create_von_mises_truss(const Parameters &p);

    std::unique_ptr<Model>
    create_catenary(const Parameters &p);

    std::unique_ptr<Model>
    create_plane_string(const Parameters &p);

    /** Model 'plane barrier': net, post and retaining rope with a brake
     * in a longitudinal section of a 2D problem. */
    std::unique_ptr<Model>
    create_plane_barrier(const Parameters &p);

    std::unique_ptr<Model>
    create_circular_membrane(const Parameters &p);

    std::unique_ptr<Model>
    create_square_membrane(const Parameters &p);

    std::unique_ptr<Model>
    create_sliding_ring(const Parameters &p);

    std::unique_ptr<Model>
    create_brake_test(const Parameters &p);

    std::unique_ptr<Model>
    create_midspan_cable(const Parameters &p);

    std::unique_ptr<Model>
    create_line_from_file(const Parameters &p);
    /** @} */
  } // namespace StructureModels
} // namespace Talus

#endif
