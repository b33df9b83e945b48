/* model_description.c -- writes modelDescription.xml (FMI 2.0 section 2.2
 * and 4.3) from the variable table of variables.c and the compiled-in start
 * parameters, so the XML and the binary cannot disagree. A build tool:
 *   rtb_fmu_model_description OUT.xml
 * Same build -> same bytes (no timestamp: generationDateAndTime is optional).
 */
#include <stdio.h>
#include <string.h>

#include "fmu_instance.h"
#include "variables.h"

static void put_escaped(FILE *f, const char *s) {
  for (; *s; ++s) {
    switch (*s) {
      case '&': fputs("&amp;", f); break;
      case '<': fputs("&lt;", f); break;
      case '>': fputs("&gt;", f); break;
      case '"': fputs("&quot;", f); break;
      default: fputc(*s, f);
    }
  }
}

static void header(FILE *f) {
  char guid[40];
  rtb_info info;
  rtb_get_info(&info);
  fprintf(f,
          "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
          "<fmiModelDescription\n"
          "  fmiVersion=\"2.0\"\n"
          "  modelName=\"rt_bushing\"\n"
          "  guid=\"%s\"\n"
          "  description=\"Six-axis rubber bushing: RT model of Puel, Bourgeteau and Aubry (2013) "
          "on x y z rx ry rz; one rt_bushing step per communication step\"\n"
          "  generationTool=\"rt_bushing %s (ABI %d)\"\n"
          "  variableNamingConvention=\"flat\"\n"
          "  numberOfEventIndicators=\"0\">\n"
          "  <CoSimulation\n"
          "    modelIdentifier=\"rt_bushing\"\n"
          "    needsExecutionTool=\"false\"\n"
          "    canHandleVariableCommunicationStepSize=\"true\"\n"
          "    canInterpolateInputs=\"false\"\n"
          "    maxOutputDerivativeOrder=\"0\"\n"
          "    canRunAsynchronuously=\"false\"\n"
          "    canBeInstantiatedOnlyOncePerProcess=\"false\"\n"
          "    canNotUseMemoryManagementFunctions=\"false\"\n"
          "    canGetAndSetFMUstate=\"true\"\n"
          "    canSerializeFMUstate=\"true\"\n"
          "    providesDirectionalDerivative=\"false\"/>\n",
          fmu_guid(guid), info.version, info.abi_version);
}

/* Each distinct unit once, in order of first use. */
static void unit_definitions(FILE *f, const rtb_bushing6_params *p) {
  char seen[64][40];
  int n = 0;
  fmu_var v;
  fputs("  <UnitDefinitions>\n", f);
  for (int i = 0; fmu_variable(i, p, &v); ++i) {
    if (!v.unit[0]) continue;
    int k = 0;
    while (k < n && strcmp(seen[k], v.unit) != 0) ++k;
    if (k < n || n == 64) continue;
    snprintf(seen[n++], sizeof seen[0], "%s", v.unit);
    fputs("    <Unit name=\"", f);
    put_escaped(f, v.unit);
    fputs("\"/>\n", f);
  }
  fputs("  </UnitDefinitions>\n", f);
}

static void log_categories(FILE *f) {
  fputs("  <LogCategories>\n"
        "    <Category name=\"logStatusWarning\" description=\"a step that did not reach the "
        "Newton tolerance (committed)\"/>\n"
        "    <Category name=\"logStatusDiscard\" description=\"a step the element could not "
        "take\"/>\n"
        "    <Category name=\"logStatusError\" description=\"bad calls and bad values\"/>\n"
        "    <Category name=\"logAll\" description=\"everything else (only when logging is "
        "on)\"/>\n"
        "  </LogCategories>\n"
        "  <DefaultExperiment startTime=\"0\" stepSize=\"0.001\"/>\n",
        f);
}

static void variable(FILE *f, const fmu_var *v) {
  static const char *const kCausality[] = {"", "input", "output", "parameter", "parameter"};
  static const char *const kVariability[] = {"", "continuous", "continuous", "tunable", "fixed"};
  fprintf(f, "    <ScalarVariable name=\"%s\" valueReference=\"%u\" causality=\"%s\" "
             "variability=\"%s\"",
          v->name, v->vr, kCausality[v->role], kVariability[v->role]);
  if (v->role == FMU_OUTPUT) fputs(" initial=\"calculated\"", f);
  if (v->role == FMU_TUNABLE || v->role == FMU_FIXED) fputs(" initial=\"exact\"", f);
  fputs(" description=\"", f);
  put_escaped(f, v->description);
  fputs("\">\n      ", f);
  if (v->type == FMU_REAL) {
    fputs("<Real", f);
    if (v->role != FMU_OUTPUT) fprintf(f, " start=\"%.17g\"", v->start);
    if (v->unit[0]) {
      fputs(" unit=\"", f);
      put_escaped(f, v->unit);
      fputs("\"", f);
    }
    fputs("/>", f);
  } else if (v->type == FMU_INTEGER) {
    fprintf(f, "<Integer start=\"%d\"/>", (int)v->start);
  } else {
    fprintf(f, "<Boolean start=\"%s\"/>", v->start != 0.0 ? "true" : "false");
  }
  fputs("\n    </ScalarVariable>\n", f);
}

/* Outputs have no direct feedthrough: an input set at t acts at the next
 * fmi2DoStep, so dependencies="" (FMI 2.0 section 2.2.8). At initialization
 * the outputs are the static forces of the initial inputs: all knowns. */
static void model_structure(FILE *f, const rtb_bushing6_params *p) {
  fmu_var v;
  fputs("  <ModelStructure>\n    <Outputs>\n", f);
  for (int i = 0; fmu_variable(i, p, &v); ++i)
    if (v.role == FMU_OUTPUT) fprintf(f, "      <Unknown index=\"%d\" dependencies=\"\"/>\n", i + 1);
  fputs("    </Outputs>\n    <InitialUnknowns>\n", f);
  for (int i = 0; fmu_variable(i, p, &v); ++i)
    if (v.role == FMU_OUTPUT) fprintf(f, "      <Unknown index=\"%d\"/>\n", i + 1);
  fputs("    </InitialUnknowns>\n  </ModelStructure>\n", f);
}

int main(int argc, char **argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: %s OUT.xml\n", argv[0]);
    return 2;
  }
  rtb_bushing6_params p;
  fmu_start_params(&p);
  int bad = -1;
  if (rtb_bushing6_validate(&p, &bad) != RTB_OK) {
    fprintf(stderr, "%s: the compiled-in parameters are invalid (axis %s)\n", argv[0],
            bad >= 0 ? rtb_axis_name(bad) : "-");
    return 1;
  }
  FILE *f = fopen(argv[1], "w");
  if (!f) {
    perror(argv[1]);
    return 1;
  }
  header(f);
  unit_definitions(f, &p);
  log_categories(f);
  fputs("  <ModelVariables>\n", f);
  fmu_var v;
  for (int i = 0; fmu_variable(i, &p, &v); ++i) variable(f, &v);
  fputs("  </ModelVariables>\n", f);
  model_structure(f, &p);
  fputs("</fmiModelDescription>\n", f);
  if (fclose(f) != 0) {
    perror(argv[1]);
    return 1;
  }
  return 0;
}
