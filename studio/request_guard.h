#pragma once
// Who may ask the studio. It listens on 127.0.0.1 only, but every page the user's browser
// opens can send requests there, so a request is answered only when
//   - its Host names the studio itself, 127.0.0.1:PORT or localhost:PORT: a page of another
//     site whose name was made to point at 127.0.0.1 (DNS rebinding) sends its own name
//     and may read nothing, not even GET /api/state with the program's source;
//   - and, when it may change something (any method but GET and HEAD), its Origin is the
//     studio's own page (http://127.0.0.1:PORT or http://localhost:PORT) and it carries the
//     page's token in X-Ontogen-Token: a token made at random for each run of the studio
//     and written into the page it serves, which another site can neither read nor guess.
//     A "simple" cross-site POST (text/plain, no preflight) has neither.

#include <cstdint>
#include <string>
#include <string_view>

#include "studio/http_server.h"

namespace ontogen::studio {

/// The header a state-changing request carries the page's token in (lower case, as
/// HttpRequest::headers holds it).
inline constexpr const char* kTokenHeader = "x-ontogen-token";

/// A token for one run of the studio: 32 bytes (256 bits) from the system's CSPRNG
/// (getrandom), as 64 lower-case hex digits. Throws std::runtime_error when the system
/// gives no random bytes.
std::string randomToken();

/// Whether two tokens are equal, in a time that depends on their lengths only.
bool sameToken(std::string_view a, std::string_view b);

/// Why the studio refuses a request that arrived at `port`, in a short sentence for the
/// answer (403); empty when it is answered. `token` is the run's token.
std::string refusalOf(const HttpRequest& request, uint16_t port, std::string_view token);

}  // namespace ontogen::studio
