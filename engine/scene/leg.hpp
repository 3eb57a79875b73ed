// The graphical model of the patient (paper §3.2, Fig. 5): a supine adult's legs on an exam table,
// in world LPS millimetres. The right leg is examined; its anterior-medial thigh, over the femoral
// vessels, carries the exam patch: a separate grid mesh whose vertices the dynamics will move every
// frame, sampled from the same surface as the leg so that it fills the hole left for it exactly.
//
// Axes: +x patient's left, +y posterior (down, towards the table), +z superior (towards the head).
// z = 0 is the groin crease; the knee is near z = -440, the ankle near z = -820.
#pragma once

#include "core/pose.hpp"
#include "core/probe_spec.hpp"
#include "core/skin_surface.hpp"
#include "scene/mesh.hpp"
#include "scene/tube.hpp"

namespace echosim::scene {

struct LegOptions {
    int rings_per_span = 16;  // the examined leg's rings between two stations (about 8 mm apart on the thigh)
    int segments = 96;        // vertices around it
    int patch_refine = 4;     // patch vertices per leg cell edge
    // The other leg, only ever seen, at a third of the triangles: its vertices are work that a CPU
    // device does on one thread every frame (the window ran 8 % faster without most of them), and
    // 8 rings a span (15 mm apart) and 64 segments still draw its outline without a visible corner.
    int other_rings_per_span = 8;
    int other_segments = 64;
};

// The exam patch: a (rows x cols) vertex grid, row-major; rows run from superior to inferior along
// the thigh, columns around it from medial towards anterior. Border vertices coincide with the leg.
struct ExamPatch {
    int rows = 0;
    int cols = 0;
    Mesh rest;          // rest shape; the scene pass draws a copy whose positions change
    float t0 = 0, t1 = 0;          // extent along the exam limb (tube parameter)
    float theta0 = 0, theta1 = 0;  // extent around it [rad]
};

class LegModel : public SkinSurface {
public:
    explicit LegModel(const LegOptions& options = {});

    const Tube& exam_limb() const { return right_leg_; }  // the right leg, thigh to ankle
    const ExamPatch& patch() const { return patch_; }
    // Everything that never moves: both legs less the patch, feet, the draped pelvis, the table.
    const Mesh& static_mesh() const { return static_mesh_; }

    // The skin at (u, v) in [0,1]^2 of the patch (u along the limb from superior, v around from
    // medial towards anterior): its point [mm] and outward unit normal.
    glm::vec3 patch_point(float u, float v) const override;
    glm::vec3 patch_normal(float u, float v) const override;

    // A probe resting on the skin at (u, v) of the patch in transverse orientation: the array
    // across the thigh, the beam along the inward normal.
    Pose probe_rest_pose(float u, float v) const;

private:
    LegOptions options_;
    Tube right_leg_, left_leg_, right_foot_, left_foot_, pelvis_;
    ExamPatch patch_;
    Mesh static_mesh_;
};

// The linear vascular probe in its own frame (origin at the centre of the face, +x along the array,
// +y into the tissue, so the body extends towards -y), its face the size `spec` gives (x by z).
Mesh make_linear_probe(const ProbeSpec& spec = kLinearProbe);

}  // namespace echosim::scene
