// header_writer.cpp -- see header_writer.h.
//
// The initializer is positional (designated initializers are C99 but not
// C++17) and follows struct rtb_params of rt_bushing.h field by field; the
// generated header pins the layout it was written for with compile-time
// checks that work in both languages (negative array size on mismatch).
#include "io/header_writer.h"

#include <cmath>
#include <cstring>
#include <string>

#include "io/number_text.h"
#include "io/params_json.h"

namespace rtb {
namespace {

const char *const kKeywords[] = {
    // C99 / C11
    "auto", "break", "case", "char", "const", "continue", "default", "do", "double", "else",
    "enum", "extern", "float", "for", "goto", "if", "inline", "int", "long", "register",
    "restrict", "return", "short", "signed", "sizeof", "static", "struct", "switch", "typedef",
    "union", "unsigned", "void", "volatile", "while", "_Bool", "_Complex", "_Imaginary",
    // C++17
    "alignas", "alignof", "and", "and_eq", "asm", "bitand", "bitor", "bool", "catch",
    "char16_t", "char32_t", "class", "compl", "constexpr", "const_cast", "decltype", "delete",
    "dynamic_cast", "explicit", "export", "false", "friend", "mutable", "namespace", "new",
    "noexcept", "not", "not_eq", "nullptr", "operator", "or", "or_eq", "private", "protected",
    "public", "reinterpret_cast", "static_assert", "static_cast", "template", "this",
    "thread_local", "throw", "true", "try", "typeid", "typename", "using", "virtual", "wchar_t",
    "xor", "xor_eq",
    // C++20 and common macros that would break the header
    "char8_t", "concept", "consteval", "constinit", "co_await", "co_return", "co_yield",
    "requires", "NULL", "main"};

// Identifiers of rt_bushing.h (and rtb_internal.h) a constant must not shadow.
const char *const kLibraryNames[] = {
    "rtb_params", "rtb_state", "rtb_settings", "rtb_status", "rtb_model", "rtb_integrator",
    "rtb_info", "rtb_real", "rtb_stage", "rtb_params_default", "rtb_params_validate",
    "rtb_settings_default", "rtb_status_message", "rtb_params_check", "RTB_PARAM_FIELDS",
    "RTB_MAX_BRANCHES", "rtb_state_init", "rtb_step", "rtb_evaluate",
    "rtb_commit", "rtb_cell_states", "rtb_get_info", "rtb_static_force", "RTB_ABI_VERSION",
    "RTB_MAX_CELLS", "RTB_DEFAULT_CELLS", "RTB_N_RESERVED", "RTB_SCALAR_BYTES", "RTB_ALPHA_MIN",
    "RTB_DT_MIN", "RTB_DT_MAX", "RTB_X_MAX", "RTB_OK", "RTB_NOT_CONVERGED", "RTB_ERR_NULL",
    "RTB_ERR_ABI", "RTB_ERR_MODEL", "RTB_ERR_CELLS", "RTB_ERR_PARAM_NONFINITE",
    "RTB_ERR_PARAM_RANGE", "RTB_ERR_ALPHA", "RTB_ERR_RESERVED", "RTB_ERR_INPUT", "RTB_ERR_DT",
    "RTB_ERR_STATE", "RTB_ERR_OVERFLOW", "RTB_ERR_SETTINGS", "RTB_MODEL_RT", "RTB_MODEL_STS",
    "RTB_INTEGRATOR_SDIRK2", "RTB_INTEGRATOR_BE", "RT_BUSHING_H", "rtb_step_info", "rtb_step_ex",
    "rtb_evaluate_ex", "RTB_ERR_ALIAS", "RTB_ERR_CAPACITY", "RTB_API", "RTB_STACK_FRAME_MAX",
    "RTB_STACK_DEPTH_MAX",
    // six-axis section
    "rtb_axis", "rtb_bushing6_params", "rtb_bushing6_state", "rtb_bushing6_params_default",
    "rtb_bushing6_validate", "rtb_bushing6_init", "rtb_bushing6_evaluate", "rtb_bushing6_commit",
    "rtb_bushing6_step", "rtb_axis_name", "RTB_AXES", "RTB_AXIS_X", "RTB_AXIS_Y", "RTB_AXIS_Z",
    "RTB_AXIS_RX", "RTB_AXIS_RY", "RTB_AXIS_RZ"};

}  // namespace

std::string comment_safe(const std::string &s) {
  std::string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    const char next = i + 1 < s.size() ? s[i + 1] : '\0';
    if ((unsigned char)c < 0x20 || c == 0x7f) {
      out += ' ';
    } else if ((c == '*' && next == '/') || (c == '/' && next == '*') ||
               (c == '?' && next == '?')) {
      out += c;
      out += ' ';
    } else {
      out += c;
    }
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == '\\')) out.pop_back();
  return out;
}

namespace {

std::string hexf(double v) { return number_text("%a", v); }
std::string dec(double v) { return number_text("%.17g", v); }
std::string short_dec(double v) { return number_text("%.6g", v); }

struct Field {
  const char *name;
  double rtb_params::*member;
  const char *note;
};

// The real fields of struct rtb_params after its four int fields, in order
// (rt_bushing.h, RTB_PARAM_FIELDS).
#define RTB_HEADER_FIELD(name, rule, kind, unit, text) {#name, &rtb_params::name, text},
const Field kRealFields[] = {RTB_PARAM_FIELDS(RTB_HEADER_FIELD)};
#undef RTB_HEADER_FIELD

// A compile-time check of the struct layout this file assumes: four leading
// int fields, then the list's fields back to back, then `reserved`.
#define RTB_HEADER_OFFSET(name, rule, kind, unit, text) offsetof(rtb_params, name),
constexpr size_t kOffsets[] = {RTB_PARAM_FIELDS(RTB_HEADER_OFFSET) offsetof(rtb_params, reserved)};
#undef RTB_HEADER_OFFSET
constexpr bool fields_back_to_back() {
  for (size_t i = 0; i + 1 < sizeof kOffsets / sizeof kOffsets[0]; ++i)
    if (kOffsets[i + 1] != kOffsets[i] + sizeof(rtb_real)) return false;
  return true;
}
static_assert(offsetof(rtb_params, abi_version) == 0 &&
                  offsetof(rtb_params, model) == sizeof(int) &&
                  offsetof(rtb_params, cells) == 2 * sizeof(int) &&
                  offsetof(rtb_params, integrator) == 3 * sizeof(int) &&
                  kOffsets[0] == 4 * sizeof(int),
              "rtb_params: the header writer assumes four leading int fields");
static_assert(fields_back_to_back() &&
                  sizeof(rtb_params) ==
                      offsetof(rtb_params, reserved) + RTB_N_RESERVED * sizeof(rtb_real),
              "rtb_params and RTB_PARAM_FIELDS disagree: update the list in rt_bushing.h");

}  // namespace

bool is_valid_header_name(const std::string &name, std::string *why) {
  auto no = [&](const std::string &reason) {
    if (why) *why = reason;
    return false;
  };
  if (name.empty()) return no("the name is empty");
  auto alpha_ = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_'; };
  auto digit = [](char c) { return c >= '0' && c <= '9'; };
  if (!alpha_(name[0])) return no("a C identifier must start with a letter or '_'");
  for (char c : name)
    if (!alpha_(c) && !digit(c))
      return no(std::string("a C identifier may contain only letters, digits and '_' (found '") +
                c + "')");
  for (const char *k : kKeywords)
    if (name == k) return no("\"" + name + "\" is a C/C++ keyword or reserved name");
  if (name.size() >= 2 && name[0] == '_' && (name[1] == '_' || (name[1] >= 'A' && name[1] <= 'Z')))
    return no("identifiers starting with \"__\" or \"_\" + capital are reserved");
  for (const char *k : kLibraryNames)
    if (name == k) return no("\"" + name + "\" is already declared by rt_bushing.h");
  if (name.size() > 200) return no("the name is longer than 200 characters");
  return true;
}

std::string emit_parameter_header(const rtb_params &p, const HeaderInfo &info) {
  std::string why;
  if (!is_valid_header_name(info.name, &why))
    throw InputError("invalid header name \"" + comment_safe(info.name) + "\": " + why);
  const char *bad = "";
  const rtb_status st = rtb_params_check(&p, &bad);
  if (st != RTB_OK)
    throw InputError(std::string("cannot write a header for invalid parameters: ") + bad + ": " +
                     rtb_status_message(st));

  const std::string &N = info.name;
  const std::string guard = "RTB_PARAMS_H_" + N;
  const bool rt = p.model == RTB_MODEL_RT;
  std::string h;
  auto line = [&](const std::string &s) {
    h += s;
    h += '\n';
  };

  // ---- provenance
  line("/* " + N + ".h -- rt_bushing parameter set \"" + N + "\".");
  line(" *");
  line(" * Generated by " + comment_safe(info.tool_version.empty() ? "rtb" : info.tool_version) +
       "; do not edit, regenerate instead.");
  line(" * Numbers are C99/C++17 hexadecimal floating literals (exact to the bit);");
  line(" * each comment gives the decimal value.");
  line(" *");
  line(std::string(" * Model: ") + (rt ? "rt (rate-dependent triboelastic, eq. (2))" : "sts (friction, section 3.1)") +
       ", cells N = " + std::to_string(p.cells) +
       (rt ? std::string(", integrator ") + integrator_name(p.integrator) : std::string()) +
       (rt && p.smoothing > 0.0 ? ", eq. (14) smoothing s = " + short_dec(p.smoothing)
                                : std::string()));
  if (!info.data_files.empty()) {
    line(" *");
    line(" * Data (SHA-256 of the file bytes):");
    for (const HeaderDataFile &f : info.data_files) {
      line(" *   " + comment_safe(f.path));
      std::string d = " *     sha256 " + comment_safe(f.sha256.empty() ? "(none)" : f.sha256);
      if (f.samples) d += ", " + std::to_string(f.samples) + " samples";
      if (std::isfinite(f.error)) d += ", error " + short_dec(f.error);
      line(d);
    }
  }
  if (std::isfinite(info.error)) {
    line(" *");
    line(" * Error: " + comment_safe(info.error_label) + " = " + short_dec(info.error) + " (" +
         number_text("%.4g", 100.0 * info.error) + " %)");
  }
  if (!info.std_devs.empty()) {
    line(" *");
    line(" * Standard deviations:");
    for (const auto &kv : info.std_devs) line(" *   " + comment_safe(kv.first) + " " + short_dec(kv.second));
  }
  if (!info.provenance.empty()) {
    line(" *");
    line(" * Provenance:");
    for (const std::string &pl : info.provenance) {
      size_t start = 0;
      for (;;) {
        const size_t nl = pl.find('\n', start);
        line(" *   " + comment_safe(pl.substr(start, nl == std::string::npos ? std::string::npos
                                                                           : nl - start)));
        if (nl == std::string::npos) break;
        start = nl + 1;
      }
    }
  }
  line(" *");
  line(" * Use:");
  line(" *   rtb_state s;");
  line(" *   rtb_state_init(&s, &" + N + ", 0.0);");
  line(" *   rtb_step(&s, &" + N + ", NULL, x, dt, &force);");
  line(" */");
  line("#ifndef " + guard);
  line("#define " + guard);
  line("");
  line("#include \"rt_bushing.h\"");
  line("");
  h += layout_checks(N, p.cells);
  line("");
  h += "static const rtb_params " + N + " = " + params_initializer(p, info.std_devs, "") + ";\n";
  line("");
  line("#endif /* " + guard + " */");
  return h;
}

std::string layout_checks(const std::string &N, int cells) {
  std::string h;
  auto line = [&](const std::string &s) {
    h += s;
    h += '\n';
  };
  line("/* Compile-time checks (C99 and C++): fail to compile against a library");
  line(" * whose parameter layout differs from the one this file was written for. */");
  line("typedef char " + N + "_check_abi[(RTB_ABI_VERSION == " + std::to_string(RTB_ABI_VERSION) +
       ") ? 1 : -1];");
  line("typedef char " + N + "_check_scalar[(RTB_SCALAR_BYTES == " +
       std::to_string(sizeof(rtb_real)) + ") ? 1 : -1];");
  line("typedef char " + N + "_check_real[(sizeof(rtb_real) == " + std::to_string(sizeof(rtb_real)) +
       ") ? 1 : -1];");
  line("typedef char " + N + "_check_reserved[(RTB_N_RESERVED == " +
       std::to_string(RTB_N_RESERVED) + ") ? 1 : -1];");
  line("typedef char " + N + "_check_cells[(RTB_MAX_CELLS >= " + std::to_string(cells) +
       ") ? 1 : -1];");
  return h;
}

// The braced initializer, in the field order of struct rtb_params.
std::string params_initializer(const rtb_params &p, const std::map<std::string, double> &std_devs,
                               const std::string &indent) {
  std::string h = "{\n";
  auto line = [&](const std::string &s) {
    h += indent + s;
    h += '\n';
  };
  line("  " + std::to_string(p.abi_version) + ", /* abi_version */");
  line(std::string("  ") + (p.model == RTB_MODEL_RT ? "RTB_MODEL_RT" : "RTB_MODEL_STS") +
       ", /* model */");
  line("  " + std::to_string(p.cells) + ", /* cells */");
  line(std::string("  ") +
       (p.integrator == RTB_INTEGRATOR_BE ? "RTB_INTEGRATOR_BE" : "RTB_INTEGRATOR_SDIRK2") +
       ", /* integrator */");
  for (const Field &f : kRealFields) {
    const double v = p.*(f.member);
    std::string c = "  " + hexf(v) + ", /* " + f.name + " = " + dec(v);
    const auto sd = std_devs.find(f.name);
    if (sd != std_devs.end()) c += " (sd " + short_dec(sd->second) + ")";
    c += std::string(": ") + f.note + " */";
    line(c);
  }
  line("  { /* reserved[" + std::to_string(RTB_N_RESERVED) + "], zero */");
  for (int i = 0; i < RTB_N_RESERVED; i += 4) {
    std::string r = "   ";
    for (int k = i; k < i + 4 && k < RTB_N_RESERVED; ++k)
      r += " " + hexf(p.reserved[k]) + (k + 1 < RTB_N_RESERVED ? "," : "");
    line(r);
  }
  line("  }");
  h += indent + "}";
  return h;
}

}  // namespace rtb
