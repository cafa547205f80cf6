#pragma once
// Input quoted in a message, made safe for a terminal.
#include <string>
#include <string_view>

namespace gs {

// Text from a file or the command line as a message may quote it: control characters (ESC
// included, which would drive the terminal), C1 controls and bytes that are not UTF-8 as \xNN;
// UTF-8 text kept; at most `max_bytes` of the text, then "...". The messages that quote input go
// through it, and the command line's error line as a whole.
std::string escaped(std::string_view text, std::size_t max_bytes = std::string_view::npos);

}  // namespace gs
