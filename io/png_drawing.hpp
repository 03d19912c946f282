#pragma once
// What every cairo picture of cdem shares: writing the PNG atomically, "nice" axis ticks, and
// aligned text. Pixel units throughout.
#include <cairo.h>

#include <filesystem>
#include <string>

namespace cdem {

// Ends a drawing: releases the context, writes the surface atomically (temp file, then rename)
// and releases the surface whether or not the write succeeded; throws std::runtime_error naming
// the file when it cannot be written.
void finish_png(cairo_t* cr, cairo_surface_t* surface, const std::filesystem::path& png);

// A "nice" tick step (1, 2 or 5 x 10^k) giving about `count` ticks over `span`.
double tick_step(double span, int count);

// Draws `s` with its box aligned on (x, y): align 0 = left / top, 0.5 = centre, 1 = right / bottom.
void draw_text(cairo_t* cr, double x, double y, const std::string& s, double align_x = 0.5,
               double align_y = 0.5);

// A tick label: %g, with values within 1e-12 of zero written as 0.
std::string tick_label(double v);

// The length (m) of the scale bar of a picture `extent` m across: the largest 1, 2 or 5 x 10^k m
// not longer than a quarter of it.
double scale_bar_length(double extent);

// A scale bar `length` m long at `px_per_m`, `thickness` px thick, its top left corner at
// (x, y), labelled in mm to its right in the current font.
void draw_scale_bar(cairo_t* cr, double x, double y, double px_per_m, double length,
                    double thickness);

}  // namespace cdem
