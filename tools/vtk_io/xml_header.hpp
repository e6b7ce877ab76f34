// VTK's XML readers trust the header of a file. Two kinds of header take a reader down before it
// reports anything: elements nested some 100000 deep (the parser frees its element tree
// recursively, one stack frame per level, and overflows the stack), and sizes far beyond what
// the file holds (NumberOfComponents="2000000000" makes vtkXMLReader::CreateArray loop over two
// billion component names; NumberOfPoints="3000000000" makes it allocate tens of GB) or below
// zero (NumberOfCells="-1" sizes a memset in vtkXMLUnstructuredGridReader::SetupOutputData).
// The files are scanned for both before VTK sees them.
#pragma once

#include <cstdint>
#include <string>

namespace tetray::vtkio {

// Deeper than any VTK file (VTKFile > UnstructuredGrid > Piece > PointData > DataArray is 5).
inline constexpr int kMaxXmlDepth = 64;

// More components than any array of a finite-element field has (a 3x3 tensor has 9).
inline constexpr std::int64_t kMaxComponents = 1024;

// zlib, the compressor VTK writes by default, shrinks data at most 1032 times; LZ4 less; LZMA
// more on runs of one byte. A compressed file may announce this many values per byte it holds.
inline constexpr std::int64_t kMaxValuesPerCompressedByte = 1 << 14;

// Empty when the elements of the XML file nest at most kMaxXmlDepth deep and every size its
// elements announce (NumberOfComponents, NumberOfPoints, NumberOfCells, NumberOfTuples, ...)
// fits the file: none negative (nor an offset, ghost level or time step), uncompressed every
// value takes at least one byte, and an appended data offset lies inside the file; and point
// coordinates have 3 components. Else what is wrong.
// The scan stops at raw appended data (binary, not XML), so a large .vtu costs only its header.
std::string xml_header_problem(const std::string& path);

}  // namespace tetray::vtkio
