/* T-BAGS DEM toolkit: word parsing for the code compiled into both engines (yarn_table.cpp, the
   LIGGGHTS adapters), which cannot use LAMMPS's utils:: (LIGGGHTS has none). */
#ifndef TBAGS_PARSE_WORDS_H
#define TBAGS_PARSE_WORDS_H

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace tbags {

// a whole word as a finite number: "1e-3" yes; "1e-3x", "", "nan", "1e999" no
inline bool to_number(const char *w, double &x)
{
  char *end = nullptr;
  errno = 0;
  x = std::strtod(w, &end);
  return end != w && *end == '\0' && errno == 0 && std::isfinite(x);
}

// the words of a line, without its '#' comment
inline std::vector<std::string> words(const std::string &line)
{
  std::istringstream in(line.substr(0, line.find('#')));
  std::vector<std::string> w;
  for (std::string s; in >> s;) w.push_back(s);
  return w;
}

}    // namespace tbags

#endif
