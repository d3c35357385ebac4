#!/usr/bin/env python3
"""Draws mote's bundled office floor plan: a 20 m x 15 m building at 5 cm per pixel.

Writes floorplan.pgm (binary P5, 400 x 300, white free, black occupied, gray unknown) and
floorplan.yaml (ROS map_server format) next to this script. Only the standard library is used,
and the output is a pure function of this file, so rerunning it reproduces the committed map.

Layout, in metres in the map frame (x right, y up, origin at the lower-left pixel):
an east-west corridor (y 6.5..8.5) splits the building; four rooms of different widths lie
south of it, an open-plan office with desks and two rooms lie north of it. Doors, furniture,
pillars and an L-shaped kitchen counter are placed without symmetry, so that a scan seen in
one place is unlikely to be seen elsewhere (global localization needs that).
"""

import math
import os

RESOLUTION = 0.05  # m per pixel
WIDTH, HEIGHT = 400, 300  # pixels
ORIGIN = (-2.0, -1.0, 0.0)  # map frame pose of the lower-left pixel (x m, y m, yaw rad)
FREE, OCCUPIED, UNKNOWN = 254, 0, 205
WALL = 0.15  # m, wall thickness
DOOR = 1.0  # m, door width

# Building envelope in image-independent grid metres (0..20 x 0..15).
X0, Y0, X1, Y1 = 0.5, 0.5, 19.5, 14.5
CORRIDOR_Y0, CORRIDOR_Y1 = 6.5, 8.5


class Canvas:
    """A grid of pixel values; (0, 0) is the lower-left pixel, as in the map frame."""

    def __init__(self):
        self.rows = [[UNKNOWN] * WIDTH for _ in range(HEIGHT)]

    def rect(self, x0, y0, x1, y1, value):
        """Fills every pixel whose centre lies in [x0, x1] x [y0, y1] (metres)."""
        i0, i1 = max(0, round(x0 / RESOLUTION)), min(WIDTH, round(x1 / RESOLUTION))
        j0, j1 = max(0, round(y0 / RESOLUTION)), min(HEIGHT, round(y1 / RESOLUTION))
        for j in range(j0, j1):
            row = self.rows[j]
            for i in range(i0, i1):
                row[i] = value

    def disc(self, cx, cy, radius, value):
        """Fills every pixel whose centre lies within radius (m) of (cx, cy)."""
        for j in range(HEIGHT):
            for i in range(WIDTH):
                px, py = (i + 0.5) * RESOLUTION, (j + 0.5) * RESOLUTION
                if math.hypot(px - cx, py - cy) <= radius:
                    self.rows[j][i] = value

    def hwall(self, y, x0, x1, doors=()):
        """A horizontal wall at height y from x0 to x1 with door openings starting at `doors`."""
        self.rect(x0, y - WALL / 2, x1, y + WALL / 2, OCCUPIED)
        for d in doors:
            self.rect(d, y - WALL, d + DOOR, y + WALL, FREE)

    def vwall(self, x, y0, y1, doors=()):
        """A vertical wall at x from y0 to y1 with door openings starting at `doors`."""
        self.rect(x - WALL / 2, y0, x + WALL / 2, y1, OCCUPIED)
        for d in doors:
            self.rect(x - WALL, d, x + WALL, d + DOOR, FREE)

    def box(self, x, y, w, h):
        """A solid piece of furniture (desk, cabinet, pillar) with lower-left corner (x, y)."""
        self.rect(x, y, x + w, y + h, OCCUPIED)


def draw_shell(c):
    c.rect(X0, Y0, X1, Y1, FREE)
    c.hwall(Y0, X0 - WALL / 2, X1 + WALL / 2)
    c.hwall(Y1, X0 - WALL / 2, X1 + WALL / 2)
    c.vwall(X0, Y0, Y1)
    c.vwall(X1, Y0, Y1)


def draw_south_rooms(c):
    # Four rooms of different widths; each door sits at a different offset within its room.
    c.hwall(CORRIDOR_Y0, X0, X1, doors=(2.3, 5.0, 10.6, 15.9))
    for x in (4.5, 9.5):
        c.vwall(x, Y0, CORRIDOR_Y0)
    c.vwall(13.0, Y0, CORRIDOR_Y0, doors=(3.0,))  # connecting door between the two east rooms
    # Room 1 (west): meeting room with an oval table of two discs and a cabinet row.
    c.disc(2.2, 3.3, 0.6, OCCUPIED)
    c.disc(2.9, 3.3, 0.6, OCCUPIED)
    c.box(0.6, 0.6, 0.5, 2.4)
    # Room 2: two desks against the south wall, one shelf on the east wall.
    c.box(5.2, 0.6, 1.6, 0.8)
    c.box(7.4, 0.6, 1.6, 0.8)
    c.box(8.9, 3.5, 0.5, 2.0)
    # Room 3: a storage room with shelves forming an aisle.
    c.box(9.9, 1.2, 2.6, 0.4)
    c.box(9.9, 3.2, 1.8, 0.4)
    # Room 4 (east, widest): an L-shaped kitchen counter and a pillar.
    c.box(17.2, 0.6, 2.2, 0.7)
    c.box(18.7, 0.6, 0.7, 3.0)
    c.box(15.0, 3.6, 0.4, 0.4)


def draw_north_side(c):
    c.hwall(CORRIDOR_Y1, X0, X1, doors=(1.2, 9.0, 12.4, 17.1))
    c.vwall(11.5, CORRIDOR_Y1, Y1)
    c.vwall(15.5, CORRIDOR_Y1, Y1, doors=(11.8,))
    c.hwall(11.0, 15.5, X1, doors=(16.8,))  # splits the north-east room in two
    # Open-plan office: a grid of desks, deliberately irregular, and two pillars.
    for x, y in ((1.5, 9.6), (3.6, 9.6), (5.7, 9.6), (1.5, 12.0), (4.4, 12.3), (7.8, 10.4)):
        c.box(x, y, 1.6, 0.8)
    c.box(6.0, 12.8, 0.4, 0.4)
    c.box(9.4, 9.4, 0.4, 0.4)
    c.box(0.6, 13.6, 3.0, 0.8)  # long cabinet along the north wall
    c.disc(9.6, 12.9, 0.5, OCCUPIED)  # round table
    # North-middle room: a sofa and a low wall part way across.
    c.box(12.0, 13.4, 2.4, 0.8)
    c.vwall(13.6, 9.2, 11.0)
    # North-east rooms: a desk each, placed differently.
    c.box(17.8, 9.0, 1.5, 0.7)
    c.box(16.0, 13.3, 0.8, 1.0)


def draw_corridor_details(c):
    # Recesses and a pillar in the corridor break its translational symmetry.
    c.box(6.8, 7.2, 0.3, 0.3)
    c.rect(14.0, CORRIDOR_Y1 - 0.2, 15.2, CORRIDOR_Y1 + 0.45, FREE)  # alcove into the north
    c.rect(14.0, CORRIDOR_Y1 + 0.45, 15.2, CORRIDOR_Y1 + 0.6, OCCUPIED)


def write_pgm(path, canvas):
    with open(path, "wb") as f:
        f.write(b"P5\n# mote bundled floor plan, made by make_floorplan.py\n")
        f.write(b"%d %d\n255\n" % (WIDTH, HEIGHT))
        for row in reversed(canvas.rows):  # image row 0 is the top (largest y)
            f.write(bytes(row))


def write_yaml(path):
    with open(path, "w", encoding="ascii") as f:
        f.write("image: floorplan.pgm\n")
        f.write("resolution: %.2f\n" % RESOLUTION)
        f.write("origin: [%.1f, %.1f, %.1f]\n" % ORIGIN)
        f.write("negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n")


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    canvas = Canvas()
    draw_shell(canvas)
    draw_south_rooms(canvas)
    draw_north_side(canvas)
    draw_corridor_details(canvas)
    write_pgm(os.path.join(here, "floorplan.pgm"), canvas)
    write_yaml(os.path.join(here, "floorplan.yaml"))


if __name__ == "__main__":
    main()
