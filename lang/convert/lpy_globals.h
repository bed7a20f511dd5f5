#pragma once
// L-Py's globals that production bodies set (`global matched; matched = 1`) and that
// nothing the word depends on reads: L-Py's tests set them to check, in their hooks'
// asserts and prints, which production applied. The block checks no assert, so such a
// global changes nothing it derives and is left out, with a warning at the body's
// `global` line. A global a production, the axiom, the derivation length, a constant
// or a hook's group, seed or value reads is state carried from production to
// production, which the block cannot say: a located error there.

#include "lang/convert/foreign_syntax.h"
#include "lang/convert/lsystem_file.h"

namespace ontogen::convert {

/// Leaves out of `file` (read whole, the hooks applied) the file's and the hooks'
/// constants of the globals production bodies set (ForeignSyntax::bodyGlobals), with a
/// warning for each; throws ConvertError at the `global` line of one that is read.
void leaveOutUnreadBodyGlobals(const ForeignSyntax& syntax, LSystemFile& file);

}  // namespace ontogen::convert
