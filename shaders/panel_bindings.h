// Bindings of the image panel pipeline, included by shaders/panel.vert, shaders/panel.frag and
// engine/render/image_panel_pass.cpp.
#ifndef ECHOSIM_PANEL_BINDINGS_H
#define ECHOSIM_PANEL_BINDINGS_H

#define PANEL_IMAGE_SET 0
#define PANEL_IMAGE_BINDING 0  // combined image sampler: the image shown, RGBA8 display values (sRGB-encoded)
#define PANEL_VERTEX_COUNT 4   // the quad over the panel's viewport, as a triangle strip

#endif
