/* T-BAGS DEM toolkit: yarn table reader and shared bond_coeff parsing (see yarn_table.h).
   Engine-neutral: compiled into the LAMMPS plugin and into LIGGGHTS (cmake/build-liggghts.sh),
   so it uses only what both have: MPI, comm->me, world and error->all(FLERR, text). */

#include "yarn_table.h"

#include "parse_words.h"

#include "comm.h"
#include "error.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

using namespace LAMMPS_NS;

namespace {

// stop all ranks with "STYLE: text" (text built with str())
void fail(LAMMPS *lmp, const char *style, const std::string &text)
{
  lmp->error->all(FLERR, (std::string(style) + ": " + text).c_str());
}

template <class T> std::string str(const T &x)
{
  std::ostringstream o;
  o << x;
  return o.str();
}

using tbags::to_number;
using tbags::words;

double number(const std::string &w, const std::string &what)
{
  double x;
  if (!to_number(w.c_str(), x)) throw std::runtime_error(what + ": '" + w + "' is not a number");
  return x;
}

// rank 0 reads the section keyword of the file into curve (throws with what is wrong)
void read_section(const std::string &file, const std::string &keyword, tbags::yarn::Curve &curve,
                  int &force_table)
{
  std::ifstream in(file);
  if (!in) throw std::runtime_error("the file is missing or unreadable");
  std::string line;
  bool found = false;
  while (!found && std::getline(in, line)) {
    const auto w = words(line);
    found = !w.empty() && w[0] == keyword;
  }
  if (!found) throw std::runtime_error("no section '" + keyword + "'");
  std::vector<std::string> head;
  while (head.empty() && std::getline(in, line)) head = words(line);
  int n = 0;
  for (size_t k = 0; k < head.size(); k++) {
    if (head[k] == "N" && k + 1 < head.size()) n = (int) number(head[++k], "the N line");
    else if (head[k] == "FORCE") force_table = 1;
    else throw std::runtime_error("unknown word '" + head[k] + "' in the N line");
  }
  if (n < 2) throw std::runtime_error("the N line needs 'N n' with n >= 2");
  for (int i = 0; i < n; i++) {
    std::vector<std::string> row;
    while (row.empty() && std::getline(in, line)) row = words(line);
    if (row.size() < 3) throw std::runtime_error("the table ends after " + str(i) + " lines");
    curve.eps.push_back(number(row[1], "row " + str(i + 1)));
    curve.val.push_back(number(row[2], "row " + str(i + 1)));
  }
}

// restart I/O: rank 0 reads count items, or stops
void fread_all(LAMMPS *lmp, void *buf, size_t size, size_t count, FILE *fp)
{
  if (fread(buf, size, count, fp) != count) fail(lmp, "yarn bond", "the restart file ends early");
}

}    // namespace

void LAMMPS_NS::read_yarn_table(LAMMPS *lmp, const char *style, const std::string &file,
                                const std::string &keyword, tbags::yarn::Curve &curve,
                                bool &force_table)
{
  // rank 0 reads and broadcasts the curve or the error
  MPI_Comm world = lmp->world;
  curve.eps.clear();
  curve.val.clear();
  int ftab = 0;
  std::string why;
  if (lmp->comm->me == 0) {
    try {
      read_section(file, keyword, curve, ftab);
    } catch (std::exception &e) {
      why = e.what();
    }
  }
  int len = (int) why.size();
  MPI_Bcast(&len, 1, MPI_INT, 0, world);
  if (len > 0) {
    why.resize(len);
    MPI_Bcast(&why[0], len, MPI_CHAR, 0, world);
    fail(lmp, style, "cannot read yarn table " + keyword + " from " + file + ": " + why);
  }
  int n = (int) curve.eps.size();
  MPI_Bcast(&n, 1, MPI_INT, 0, world);
  MPI_Bcast(&ftab, 1, MPI_INT, 0, world);
  curve.eps.resize(n);
  curve.val.resize(n);
  MPI_Bcast(curve.eps.data(), n, MPI_DOUBLE, 0, world);
  MPI_Bcast(curve.val.data(), n, MPI_DOUBLE, 0, world);
  force_table = ftab != 0;
  const char *bad = tbags::yarn::check_curve(curve);
  if (*bad) fail(lmp, style, "yarn table " + keyword + " in " + file + ": " + bad);
}

void LAMMPS_NS::parse_yarn_coeff(LAMMPS *lmp, const char *style, int narg, char **arg,
                                 YarnCoeff &c, bool axial_only)
{
  c.r0 = -1.0;
  if (narg < 4 || strcmp(arg[1], "table") != 0)
    fail(lmp, style, std::string("write 'bond_coeff T table FILE KEYWORD diameter D") +
                         (axial_only ? " r0 R0'" : " poisson NU'"));
  c.file = arg[2];
  c.keyword = arg[3];
  read_yarn_table(lmp, style, c.file, c.keyword, *c.curve, c.p.force_table);
  double E = -1.0, nu = -2.0, kappa = -1.0, brk = -1.0;
  c.p.d = -1.0;
  c.p.gn = c.p.gs = c.p.gr = 0.0;
  c.p.plastic = false;
  for (int iarg = 4; iarg < narg;) {
    const std::string kw = arg[iarg];
    auto need = [&](int n) {
      if (iarg + n >= narg) fail(lmp, style, "keyword '" + kw + "' needs " + str(n) + " value(s)");
    };
    auto num = [&](int k) {
      double x = 0.0;
      if (!to_number(arg[iarg + k], x))
        fail(lmp, style, "keyword '" + kw + "': expected a number, got '" + arg[iarg + k] + "'");
      return x;
    };
    if (kw == "diameter") {
      need(1);
      c.p.d = num(1);
      iarg += 2;
    } else if (kw == "break") {
      need(1);
      brk = num(1);
      iarg += 2;
    } else if (kw == "r0") {
      need(1);
      c.r0 = num(1);
      if (!(c.r0 > 0.0)) fail(lmp, style, "r0 must be > 0 (m), the bonds' rest length, got " + str(c.r0));
      iarg += 2;
    } else if (axial_only && kw == "damping") {
      need(1);
      c.p.gn = num(1);
      if (c.p.gn < 0.0) fail(lmp, style, "damping must be >= 0");
      iarg += 2;
    } else if (!axial_only && kw == "damping") {
      need(3);
      c.p.gn = num(1);
      c.p.gs = num(2);
      c.p.gr = num(3);
      if (c.p.gn < 0.0 || c.p.gs < 0.0 || c.p.gr < 0.0)
        fail(lmp, style, "damping coefficients must be >= 0");
      iarg += 4;
    } else if (!axial_only && kw == "unload") {
      need(1);
      if (strcmp(arg[iarg + 1], "plastic") == 0) c.p.plastic = true;
      else if (strcmp(arg[iarg + 1], "elastic") == 0) c.p.plastic = false;
      else fail(lmp, style, "unload must be elastic or plastic");
      iarg += 2;
    } else if (!axial_only && kw == "E") {
      need(1);
      E = num(1);
      iarg += 2;
    } else if (!axial_only && kw == "poisson") {
      need(1);
      nu = num(1);
      iarg += 2;
    } else if (!axial_only && kw == "shear") {
      need(1);
      kappa = num(1);
      if (kappa < 0.0)
        fail(lmp, style, "shear coefficient must be >= 0 (0: no shear spring), got " + str(kappa));
      iarg += 2;
    } else {
      fail(lmp, style, "unknown bond_coeff keyword '" + kw + "'");
    }
  }
  if (c.p.d <= 0.0)
    fail(lmp, style, "bond_coeff needs 'diameter D' with D > 0 (m)");
  if (axial_only && c.r0 <= 0.0)
    fail(lmp, style, "bond_coeff needs 'r0 R0' with R0 > 0 (m), the unstretched length");
  const double last = c.curve->eps.back();
  if (brk < 0.0) brk = last;
  if (brk <= 0.0 || brk > last)
    fail(lmp, style, "break strain " + str(brk) + " must be in (0, " + str(last) + "] (the table's last strain)");
  c.p.eps_break = brk;
  if (!axial_only) {
    if (nu <= -1.0 || nu >= 0.5)
      fail(lmp, style, "bond_coeff needs 'poisson NU' with -1 < NU < 0.5 (G = E/2(1+NU))");
    const double E0 = c.p.force_table ? c.curve->slope0() / c.p.area() : c.curve->slope0();
    if (E < 0.0) E = E0;
    if (E <= 0.0) fail(lmp, style, "E must be > 0 Pa");
    if (kappa < 0.0) kappa = 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu);    // circular section
    c.p.E = E;
    c.p.nu = nu;
    c.p.kappa = kappa;
  }
  c.set = true;
}

void LAMMPS_NS::write_yarn_coeff(FILE *fp, const YarnCoeff &c)
{
  const int set = c.set ? 1 : 0;
  fwrite(&set, sizeof(int), 1, fp);
  if (!set) return;
  const int n = (int) c.curve->eps.size();
  const int lf = (int) c.file.size() + 1, lk = (int) c.keyword.size() + 1;
  fwrite(&n, sizeof(int), 1, fp);
  fwrite(c.curve->eps.data(), sizeof(double), n, fp);
  fwrite(c.curve->val.data(), sizeof(double), n, fp);
  double v[11] = {c.p.d, c.p.E, c.p.nu, c.p.kappa, c.p.eps_break, c.p.gn, c.p.gs, c.p.gr,
                  c.p.plastic ? 1.0 : 0.0, c.p.force_table ? 1.0 : 0.0, c.r0};
  fwrite(v, sizeof(double), 11, fp);
  fwrite(&lf, sizeof(int), 1, fp);
  fwrite(c.file.c_str(), 1, lf, fp);
  fwrite(&lk, sizeof(int), 1, fp);
  fwrite(c.keyword.c_str(), 1, lk, fp);
}

void LAMMPS_NS::read_yarn_coeff(LAMMPS *lmp, FILE *fp, YarnCoeff &c)
{
  const int me = lmp->comm->me;
  MPI_Comm world = lmp->world;
  int set = 0, n = 0;
  if (me == 0) fread_all(lmp, &set, sizeof(int), 1, fp);
  MPI_Bcast(&set, 1, MPI_INT, 0, world);
  c.set = set != 0;
  if (!set) return;
  if (me == 0) fread_all(lmp, &n, sizeof(int), 1, fp);
  MPI_Bcast(&n, 1, MPI_INT, 0, world);
  c.curve->eps.resize(n);
  c.curve->val.resize(n);
  double v[11];
  if (me == 0) {
    fread_all(lmp, c.curve->eps.data(), sizeof(double), n, fp);
    fread_all(lmp, c.curve->val.data(), sizeof(double), n, fp);
    fread_all(lmp, v, sizeof(double), 11, fp);
  }
  MPI_Bcast(c.curve->eps.data(), n, MPI_DOUBLE, 0, world);
  MPI_Bcast(c.curve->val.data(), n, MPI_DOUBLE, 0, world);
  MPI_Bcast(v, 11, MPI_DOUBLE, 0, world);
  c.p.d = v[0];
  c.p.E = v[1];
  c.p.nu = v[2];
  c.p.kappa = v[3];
  c.p.eps_break = v[4];
  c.p.gn = v[5];
  c.p.gs = v[6];
  c.p.gr = v[7];
  c.p.plastic = v[8] != 0.0;
  c.p.force_table = v[9] != 0.0;
  c.r0 = v[10];
  for (std::string *s : {&c.file, &c.keyword}) {
    int len = 0;
    if (me == 0) fread_all(lmp, &len, sizeof(int), 1, fp);
    MPI_Bcast(&len, 1, MPI_INT, 0, world);
    std::vector<char> buf(len);
    if (me == 0) fread_all(lmp, buf.data(), 1, len, fp);
    MPI_Bcast(buf.data(), len, MPI_CHAR, 0, world);
    *s = buf.data();
  }
}
