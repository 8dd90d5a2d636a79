/* ggx render's images in the command's figures (render_out.c): demo, render and render --normal-map draw
 * them.
 * SPDX-License-Identifier: MIT */
#ifndef GGX_TOOL_CMD_RENDER_H
#define GGX_TOOL_CMD_RENDER_H

#include "figure_out.h"
#include "render.h"

/* The caption's words for the material (and its compensation) and the scene's tangent frame. */
void render_material_words(const render_spec *r, char *buf, size_t n);
const char *render_frame_words(render_scene scene);
/* ggx render --normal-map (cmd_render_normal_map.c). */
int render_normal_map(int argc, char **argv);

#endif
