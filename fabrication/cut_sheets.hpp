#pragma once
// Nesting and drawing of the cut sheets (Section 3.6.1): every lamella piece a part on the lamella
// sheets (strips in rows, nesting.hpp) or, with fabrication.stock "boards", on boards of the
// lamella's width and stock_length_mm long (one row each: a cutting list); every PTFE sticker a
// part on the foil sheets. Each sheet carries its id and what it is on its REFERENCE layer.
#include "fabrication/fabricate.hpp"

namespace egg::fabrication {

// Fills r.lamellaNesting, r.sheets, r.sheetIds, r.pieceSheets, r.sheetWidthSuggestion and the
// sticker counterparts from r.lamellae and r.stickers. Throws InvalidInput naming the field when a
// part does not fit an empty sheet or board.
void layOutCutSheets(FabricationResult& r);

// cut/boards.csv: board,id,piece,lamella,from_mm,to_mm,length_mm,waste_mm (the cutting list of
// linear stock: where along each board each piece lies, from its trimmed end).
std::string boardsCsv(const FabricationResult& r);

}  // namespace egg::fabrication
