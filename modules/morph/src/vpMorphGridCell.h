/*
  \file vpMorphGridCell.h
  \brief Internal to the morph module (not installed): the cell of a uniform grid that holds a coordinate.
*/
#ifndef VP_MORPH_GRID_CELL_H
#define VP_MORPH_GRID_CELL_H

/*
  The index in [0, n) of the cell holding f, a coordinate in cell units from the grid's origin; the nearest cell when
  f is outside, 0 for NaN. Clamped in floating point before the conversion: a query point may lie arbitrarily far
  from the grid, and int(f) overflows there. Shared by the grids of vpMorphNearestEdge, vpMorphOverlapPolygon and
  vpMorphInsideTest.
*/
inline int vpMorphGridCell(double f, int n)
{
  return !(f > 0.0) ? 0 : (f >= double(n - 1) ? n - 1 : int(f));
}

#endif
