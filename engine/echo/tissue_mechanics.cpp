#include "echo/tissue_mechanics.hpp"

#include "echo/bmode.hpp"

namespace echosim::echo {
namespace {

constexpr float kPa(double mmHg) { return float(mmHg * kPascalPerMmHg / 1000.0); }

TissueMechanics solid(float modulus_kpa, float max_strain, Tissue t)
{
    return {modulus_kpa > 0 ? 1.0f / modulus_kpa : 0.0f, max_strain, 0, 1, 0, 0, float(attenuation_db_cm_mhz(t)), 0};
}

TissueMechanics lumen(float onset_kpa, float width_kpa, float max_closure, float pulse, Tissue t)
{
    return {0, 0, onset_kpa, width_kpa, max_closure, pulse, float(attenuation_db_cm_mhz(t)), 0};
}

}  // namespace

TissueTable tissue_mechanics(const PatientCase& patient)
{
    const float venous = kPa(patient.venous_pressure_mmHg);
    TissueTable t{};
    for (auto& m : t) m = solid(25, 0.5f, Tissue::muscle);  // codes the phantom does not use: soft tissue
    t[int(Tissue::outside)] = solid(25, 0.5f, Tissue::muscle);  // beyond the map's edge: as the tissue around
    t[int(Tissue::skin)] = solid(80, 0.4f, Tissue::skin);
    t[int(Tissue::fat)] = solid(8, 0.7f, Tissue::fat);
    t[int(Tissue::fascia)] = solid(150, 0.3f, Tissue::fascia);
    t[int(Tissue::muscle)] = solid(25, 0.5f, Tissue::muscle);
    // the artery: its own pressure holds it open until the probe's pressure reaching it passes the
    // diastolic (80 mmHg), where its wall begins to give: the sonographer's cue that the exam force
    // is reached (about 12 N over the slim thigh's femoral vessels, the vein closed well before);
    // it loses at most 12 % to pressure and widens 6 % with each beat (femoral distension). (Half
    // the diastolic did it while the stress was taken at the tissue's depth at rest, deform_column.h.)
    t[int(Tissue::artery_lumen)] = lumen(kPa(80), kPa(40), 0.12f, 0.06f, Tissue::artery_lumen);
    t[int(Tissue::artery_wall)] = solid(600, 0.2f, Tissue::artery_wall);
    // the vein: closes over 10 mmHg above the venous pressure, walls meeting
    t[int(Tissue::vein_lumen)] = lumen(venous, kPa(10), 1.0f, 0.0f, Tissue::vein_lumen);
    t[int(Tissue::saphenous_lumen)] = lumen(venous, kPa(10), 1.0f, 0.0f, Tissue::saphenous_lumen);
    t[int(Tissue::bone_cortex)] = solid(0, 0, Tissue::bone_cortex);
    t[int(Tissue::bone_marrow)] = solid(0, 0, Tissue::bone_marrow);
    // an acute thrombus: a gel confined in the vein, hardly compressible
    t[int(Tissue::thrombus)] = solid(400, 0.2f, Tissue::thrombus);
    // a chronic one: organised, partly compressible, in a thick fibrotic wall
    t[int(Tissue::organised_thrombus)] = solid(60, 0.4f, Tissue::organised_thrombus);
    t[int(Tissue::vein_wall)] = solid(300, 0.3f, Tissue::vein_wall);
    // a chronic thrombus' vein: its wall thick and fibrotic, rigid (its own code: the phantom puts
    // it where the anatomy has a chronic thrombus, so the table needs no case)
    t[int(Tissue::scarred_vein_wall)] = solid(1500, 0.1f, Tissue::scarred_vein_wall);
    // a lymph node: firm, a little compressible, keeping its shape under the exam's pressure (the
    // mimic a trainee must not call a clot)
    t[int(Tissue::lymph_node)] = solid(50, 0.35f, Tissue::lymph_node);
    return t;
}

TissueTable paper_linear_mechanics()
{
    TissueTable t{};
    for (auto& m : t) m = solid(1, 0.9f, Tissue::muscle);
    return t;
}

}  // namespace echosim::echo
