// The graphical model of the patient (paper §3.2, Fig. 5): a supine adult's legs on an exam table,
// in world LPS millimetres. The right leg is examined; its anterior-medial thigh, over the femoral
// vessels, carries the exam patch: a separate grid mesh whose vertices the dynamics will move every
// frame, sampled from the same surface as the leg so that it fills the hole left for it exactly.
//
// Axes: +x patient's left, +y posterior (down, towards the table), +z superior (towards the head).
// z = 0 is the groin crease; the knee is near z = -440, the ankle near z = -820.
//
// The exam patch is a window that can sit anywhere on the right leg (LegOptions::patch_centre): the
// tissue simulation runs on it, and the session moves it to follow the probe from the groin to the
// knee (session/session.hpp, "The exam window"). Wherever it sits it is a block of the leg mesh's
// own cells (whole rings by whole segments) the size of the home patch's in millimetres, so the
// static mesh's hole and the patch's border always share their vertices exactly.
#pragma once

#include <optional>
#include <vector>

#include "core/pose.hpp"
#include "core/probe_spec.hpp"
#include "core/skin_surface.hpp"
#include "scene/mesh.hpp"
#include "scene/tube.hpp"

namespace echosim::scene {

// A point of the exam limb in its tube parameters: t along the stations, theta [rad] in [0, 2 pi).
struct LimbCoordinates {
    float t = 0;
    float theta = 0;
};

struct LegOptions {
    int rings_per_span = 16;  // the examined leg's rings between two stations (about 8 mm apart on the thigh)
    int segments = 96;        // vertices around it
    int patch_refine = 4;     // patch vertices per leg cell edge
    // The other leg, only ever seen, at a third of the triangles: its vertices are work that a CPU
    // device does on one thread every frame (the window ran 8 % faster without most of them), and
    // 8 rings a span (15 mm apart) and 64 segments still draw its outline without a visible corner.
    int other_rings_per_span = 8;
    int other_segments = 64;
    // Where the exam patch is centred on the right leg (tube parameters: t along the stations,
    // theta [rad] around from medial towards posterior, Tube's convention); the patch then covers
    // the whole leg cells nearest to as many millimetres along and around as the home patch does.
    // None: the home patch over the common femoral vessels (the leg's rings nearest z = -30 and
    // -150 mm, segments 278..332 degrees), where the shipped tissue model was measured.
    std::optional<LimbCoordinates> patch_centre;
};

// The leg mesh's cells a patch replaces: rings [ring0, ring1), segments [seg0, seg1), segment
// indices taken modulo LegOptions::segments (seg0 in [0, segments), seg1 may pass it).
struct PatchCells {
    int ring0 = 0, ring1 = 0, seg0 = 0, seg1 = 0;
    bool operator==(const PatchCells&) const = default;
};

// The exam patch: a (rows x cols) vertex grid, row-major; rows run from superior to inferior along
// the thigh, columns around it from medial towards anterior. Border vertices coincide with the leg.
struct ExamPatch {
    int rows = 0;
    int cols = 0;
    Mesh rest;          // rest shape; the scene pass draws a copy whose positions change
    float t0 = 0, t1 = 0;          // extent along the exam limb (tube parameter)
    float theta0 = 0, theta1 = 0;  // extent around it [rad] (theta0 may be below 0 or theta1 past 2 pi)
    PatchCells cells;   // the leg mesh's cells it replaces
    // its middle on the skin: halfway along its middle segment's line from its first ring to its
    // last, and halfway around its middle ring, in millimetres (not in t: the leg's spans differ in
    // length, so a window across the hip's short span has its t midpoint 30 mm off its middle)
    LimbCoordinates centre;
    float centre_t() const { return centre.t; }
    float centre_theta() const { return centre.theta; }
};


class LegModel : public SkinSurface {
public:
    explicit LegModel(const LegOptions& options = {});

    const LegOptions& options() const { return options_; }

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

    // Anywhere on the exam limb, not only the patch: the skin point at (t, theta), its outward
    // normal, and the probe resting there transversely (as probe_rest_pose).
    glm::vec3 limb_point(LimbCoordinates c) const { return right_leg_.point(c.t, c.theta); }
    glm::vec3 limb_normal(LimbCoordinates c) const { return right_leg_.outward_normal(c.t, c.theta); }
    Pose limb_rest_pose(LimbCoordinates c) const;
    // The limb coordinates of a world point: t of the ring through its z (the rings are planes of
    // constant z), theta its angle about that ring's centre. Exact on the skin; off it, the point
    // of the skin radially under it. t is clamped to the limb.
    LimbCoordinates limb_coordinates(glm::vec3 p) const;
    // The tube parameter t of the ring at height z [mm] (clamped to the limb).
    float limb_t_at_z(float z) const;
    // The home patch's size [mm]: along the limb (through its middle segment) and around it (through
    // its middle ring); every window is cut to the nearest whole cells of this size.
    float window_along_mm() const { return window_along_mm_; }
    float window_around_mm() const { return window_around_mm_; }
    // The cells a patch centred at `centre` would cover (what LegOptions::patch_centre makes),
    // without building it. Throws std::invalid_argument for a centre that is not finite.
    PatchCells window_cells(LimbCoordinates centre) const;

private:
    LegOptions options_;
    Tube right_leg_, left_leg_, right_foot_, left_foot_, pelvis_;
    ExamPatch patch_;
    Mesh static_mesh_;
    float window_along_mm_ = 0, window_around_mm_ = 0;
    std::vector<float> ring_z_;  // the exam limb's rings' heights [mm]
};

// The linear vascular probe in its own frame (origin at the centre of the face, +x along the array,
// +y into the tissue, so the body extends towards -y), its face the size `spec` gives (x by z). Its
// head's -x end carries the orientation marker in kMarkerColour: the side the image's left shows.
inline constexpr glm::vec3 kMarkerColour{0.30f, 0.85f, 0.40f};
Mesh make_linear_probe(const ProbeSpec& spec = kLinearProbe);

}  // namespace echosim::scene
