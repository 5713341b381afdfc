#pragma once
// The program's version (the top-level CMakeLists.txt's project version) and
// the git commit it was built from ("unknown" outside git; "+local-changes"
// when the tree differed from that commit).

namespace demcal {

const char* version();
const char* commit();

}  // namespace demcal
