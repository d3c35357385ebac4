// The figures' 5 x 7 bitmap font: one glyph a line, seven rows of five dots top to bottom ('#'
// drawn, '.' not), lower-case letters without descenders (g, p, q and y are
// squeezed into the x-height).
#include <algorithm>
#include <cctype>
#include <string_view>

#include "mote/maps/figure.hpp"

namespace mote::figure {
namespace {

struct Glyph {
  char c;
  std::string_view rows;  // 7 groups of 5 dots, separated by spaces
};

constexpr Glyph kFont[] = {
    {'0', ".###. #...# #..## #.#.# ##..# #...# .###."},
    {'1', "..#.. .##.. ..#.. ..#.. ..#.. ..#.. .###."},
    {'2', ".###. #...# ....# ...#. ..#.. .#... #####"},
    {'3', "##### ...#. ..#.. ...#. ....# #...# .###."},
    {'4', "...#. ..##. .#.#. #..#. ##### ...#. ...#."},
    {'5', "##### #.... ####. ....# ....# #...# .###."},
    {'6', "..##. .#... #.... ####. #...# #...# .###."},
    {'7', "##### ....# ...#. ..#.. .#... .#... .#..."},
    {'8', ".###. #...# #...# .###. #...# #...# .###."},
    {'9', ".###. #...# #...# .#### ....# ...#. .##.."},
    {'a', "..... ..... .###. ....# .#### #...# .####"},
    {'b', "#.... #.... #.##. ##..# #...# #...# ####."},
    {'c', "..... ..... .###. #.... #.... #...# .###."},
    {'d', "....# ....# .##.# #..## #...# #...# .####"},
    {'e', "..... ..... .###. #...# ##### #.... .###."},
    {'f', "..##. .#..# .#... ###.. .#... .#... .#..."},
    {'g', "..... ..... .#### #...# .#### ....# .###."},
    {'h', "#.... #.... #.##. ##..# #...# #...# #...#"},
    {'i', "..#.. ..... .##.. ..#.. ..#.. ..#.. .###."},
    {'j', "...#. ..... ..##. ...#. ...#. #..#. .##.."},
    {'k', "#.... #.... #..#. #.#.. ##... #.#.. #..#."},
    {'l', ".##.. ..#.. ..#.. ..#.. ..#.. ..#.. .###."},
    {'m', "..... ..... ##.#. #.#.# #.#.# #...# #...#"},
    {'n', "..... ..... #.##. ##..# #...# #...# #...#"},
    {'o', "..... ..... .###. #...# #...# #...# .###."},
    {'p', "..... ..... ####. #...# ####. #.... #...."},
    {'q', "..... ..... .#### #...# .#### ....# ....#"},
    {'r', "..... ..... #.##. ##..# #.... #.... #...."},
    {'s', "..... ..... .###. #.... .###. ....# ####."},
    {'t', ".#... .#... ###.. .#... .#... .#..# ..##."},
    {'u', "..... ..... #...# #...# #...# #..## .##.#"},
    {'v', "..... ..... #...# #...# #...# .#.#. ..#.."},
    {'w', "..... ..... #...# #...# #.#.# #.#.# .#.#."},
    {'x', "..... ..... #...# .#.#. ..#.. .#.#. #...#"},
    {'y', "..... ..... #...# #...# .#### ....# .###."},
    {'z', "..... ..... ##### ...#. ..#.. .#... #####"},
    {' ', "..... ..... ..... ..... ..... ..... ....."},
    {'.', "..... ..... ..... ..... ..... .##.. .##.."},
    {',', "..... ..... ..... ..... .##.. ..#.. .#..."},
    {'-', "..... ..... ..... ##### ..... ..... ....."},
    {'+', "..... ..#.. ..#.. ##### ..#.. ..#.. ....."},
    {'*', "..... ..#.. #.#.# .###. #.#.# ..#.. ....."},
    {'/', "..... ....# ...#. ..#.. .#... #.... ....."},
    {'(', "...#. ..#.. .#... .#... .#... ..#.. ...#."},
    {')', ".#... ..#.. ...#. ...#. ...#. ..#.. .#..."},
    {':', "..... .##.. .##.. ..... .##.. .##.. ....."},
    {'%', "##... ##..# ...#. ..#.. .#... #..## ...##"},
    {'=', "..... ..... ##### ..... ##### ..... ....."},
    {'^', "..#.. .#.#. #...# ..... ..... ..... ....."},
    {'?', ".###. #...# ....# ...#. ..#.. ..... ..#.."},
};

const Glyph& glyph(char c) {
  const char lower = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const auto* g = std::find_if(std::begin(kFont), std::end(kFont),
                               [&](const Glyph& f) { return f.c == lower; });
  return g != std::end(kFont) ? *g : kFont[std::size(kFont) - 1];
}

// Whether dot (col, row) of the glyph is drawn.
bool dot_on(const Glyph& g, int col, int row) {
  return g.rows[static_cast<std::size_t>(row * (kGlyphWidth + 1) + col)] == '#';
}

// Draws the string's dots through place(col, row) of the whole line, in font dots.
template <class Place>
void each_dot(std::string_view s, Place place) {
  for (std::size_t k = 0; k < s.size(); ++k) {
    const Glyph& g = glyph(s[k]);
    const int x0 = static_cast<int>(k) * kGlyphAdvance;
    for (int row = 0; row < kGlyphHeight; ++row) {
      for (int col = 0; col < kGlyphWidth; ++col) {
        if (dot_on(g, col, row)) place(x0 + col, row);
      }
    }
  }
}

}  // namespace

int text_width(std::string_view s, int scale) {
  return s.empty() ? 0 : (static_cast<int>(s.size()) * kGlyphAdvance - 1) * scale;
}

void text(RgbImage& image, int x, int y, std::string_view s, int scale, Rgb c) {
  each_dot(s, [&](int col, int row) {
    fill_rect(image, x + col * scale, y + row * scale, scale, scale, c);
  });
}

void text_up(RgbImage& image, int x, int y, std::string_view s, int scale, Rgb c) {
  const int bottom = y + text_width(s, scale);
  each_dot(s, [&](int col, int row) {
    fill_rect(image, x + row * scale, bottom - (col + 1) * scale, scale, scale, c);
  });
}

}  // namespace mote::figure
