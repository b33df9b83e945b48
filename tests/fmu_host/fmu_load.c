/* fmu_load.c -- see fmu_load.h.
 *
 * Unpacking: the `unzip` command (Debian package unzip) rather than libzip:
 * an FMU is an ordinary zip, the test needs the files on disk anyway for
 * dlopen, and a separate tool tests that the archive is readable by a program
 * that is not the one that wrote it.
 * XML: libxml2 (Debian libxml2-dev), a validating-grade parser, so the test
 * also fails on a malformed modelDescription.xml that a small hand parser
 * might accept.
 */
#define _GNU_SOURCE
#include "fmu_load.h"

#include <dlfcn.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void copy_attr(xmlNode *n, const char *attr, char *out, size_t cap, const char *dflt) {
  xmlChar *v = xmlGetProp(n, (const xmlChar *)attr);
  snprintf(out, cap, "%s", v ? (const char *)v : dflt);
  if (v) xmlFree(v);
}

static int attr_true(xmlNode *n, const char *attr) {
  char buf[8];
  copy_attr(n, attr, buf, sizeof buf, "false");
  return strcmp(buf, "true") == 0;
}

static int is(xmlNode *n, const char *name) {
  return n->type == XML_ELEMENT_NODE && strcmp((const char *)n->name, name) == 0;
}

static void read_variable(xmlNode *sv, md_var *v) {
  char vr[16];
  copy_attr(sv, "name", v->name, sizeof v->name, "");
  copy_attr(sv, "valueReference", vr, sizeof vr, "-1");
  v->vr = (unsigned)strtoul(vr, NULL, 10);
  copy_attr(sv, "causality", v->causality, sizeof v->causality, "local");
  copy_attr(sv, "variability", v->variability, sizeof v->variability, "continuous");
  for (xmlNode *t = sv->children; t; t = t->next) {
    if (t->type != XML_ELEMENT_NODE) continue;
    snprintf(v->type, sizeof v->type, "%s", (const char *)t->name);
    copy_attr(t, "start", v->start, sizeof v->start, "");
    copy_attr(t, "unit", v->unit, sizeof v->unit, "");
  }
}

static void read_structure(xmlNode *ms, md_info *md) {
  md->output_dependencies_empty = 1;
  for (xmlNode *o = ms->children; o; o = o->next) {
    if (!is(o, "Outputs")) continue;
    for (xmlNode *u = o->children; u; u = u->next) {
      if (!is(u, "Unknown")) continue;
      ++md->n_output_unknowns;
      char dep[64];
      copy_attr(u, "dependencies", dep, sizeof dep, "(absent)");
      if (dep[0] != '\0') md->output_dependencies_empty = 0;
    }
  }
}

static int read_model_description(const char *path, md_info *md) {
  xmlDoc *doc = xmlReadFile(path, NULL, XML_PARSE_NONET);
  if (!doc) {
    fprintf(stderr, "fmu_host: %s is not well-formed XML\n", path);
    return 0;
  }
  xmlNode *root = xmlDocGetRootElement(doc);
  int ok = root && is(root, "fmiModelDescription");
  if (ok) {
    copy_attr(root, "fmiVersion", md->fmi_version, sizeof md->fmi_version, "");
    copy_attr(root, "guid", md->guid, sizeof md->guid, "");
    for (xmlNode *n = root->children; n; n = n->next) {
      if (is(n, "CoSimulation")) {
        copy_attr(n, "modelIdentifier", md->model_identifier, sizeof md->model_identifier, "");
        md->can_get_set_state = attr_true(n, "canGetAndSetFMUstate");
        md->can_serialize_state = attr_true(n, "canSerializeFMUstate");
        md->variable_step = attr_true(n, "canHandleVariableCommunicationStepSize");
      } else if (is(n, "ModelVariables")) {
        for (xmlNode *sv = n->children; sv; sv = sv->next)
          if (is(sv, "ScalarVariable") && md->n_vars < MD_MAX_VARS)
            read_variable(sv, &md->vars[md->n_vars++]);
      } else if (is(n, "ModelStructure")) {
        read_structure(n, md);
      }
    }
  } else {
    fprintf(stderr, "fmu_host: %s: root element is not fmiModelDescription\n", path);
  }
  xmlFreeDoc(doc);
  return ok;
}

#define SYM(name) {#name, offsetof(fmi2_api, name)}
static const struct { const char *name; size_t offset; } kSymbols[] = {
    SYM(GetTypesPlatform), SYM(GetVersion), SYM(SetDebugLogging), SYM(Instantiate),
    SYM(FreeInstance), SYM(SetupExperiment), SYM(EnterInitializationMode),
    SYM(ExitInitializationMode), SYM(Terminate), SYM(Reset), SYM(GetReal), SYM(GetInteger),
    SYM(GetBoolean), SYM(GetString), SYM(SetReal), SYM(SetInteger), SYM(SetBoolean),
    SYM(SetString), SYM(GetFMUstate), SYM(SetFMUstate), SYM(FreeFMUstate),
    SYM(SerializedFMUstateSize), SYM(SerializeFMUstate), SYM(DeSerializeFMUstate),
    SYM(GetDirectionalDerivative), SYM(EnterEventMode), SYM(NewDiscreteStates),
    SYM(EnterContinuousTimeMode), SYM(CompletedIntegratorStep), SYM(SetTime),
    SYM(SetContinuousStates), SYM(GetDerivatives), SYM(GetEventIndicators),
    SYM(GetContinuousStates), SYM(GetNominalsOfContinuousStates), SYM(SetRealInputDerivatives),
    SYM(GetRealOutputDerivatives), SYM(DoStep), SYM(CancelStep), SYM(GetStatus),
    SYM(GetRealStatus), SYM(GetIntegerStatus), SYM(GetBooleanStatus), SYM(GetStringStatus)};

static int resolve(fmu_file *f) {
  for (size_t i = 0; i < sizeof kSymbols / sizeof kSymbols[0]; ++i) {
    char name[64];
    snprintf(name, sizeof name, "fmi2%s", kSymbols[i].name);
    void *p = dlsym(f->so, name);
    if (!p) {
      fprintf(stderr, "fmu_host: the binary does not export %s\n", name);
      return 0;
    }
    memcpy((char *)&f->api + kSymbols[i].offset, &p, sizeof p);
  }
  return 1;
}

int fmu_open(const char *fmu_path, fmu_file *f) {
  memset(f, 0, sizeof *f);
  snprintf(f->dir, sizeof f->dir, "/tmp/rtb_fmu_host.XXXXXX");
  if (!mkdtemp(f->dir)) {
    perror("mkdtemp");
    return 0;
  }
  char cmd[1024], path[512];
  snprintf(cmd, sizeof cmd, "unzip -q -o '%s' -d '%s'", fmu_path, f->dir);
  if (system(cmd) != 0) {
    fprintf(stderr, "fmu_host: `%s` failed\n", cmd);
    return 0;
  }
  snprintf(path, sizeof path, "%s/modelDescription.xml", f->dir);
  if (!read_model_description(path, &f->md)) return 0;
  snprintf(path, sizeof path, "%s/binaries/linux64/%s.so", f->dir, f->md.model_identifier);
  f->so = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  if (!f->so) {
    fprintf(stderr, "fmu_host: dlopen: %s\n", dlerror());
    return 0;
  }
  return resolve(f);
}

void fmu_close(fmu_file *f) {
  if (f->so) dlclose(f->so);
  f->so = NULL;
  if (f->dir[0]) {
    char cmd[512];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", f->dir);
    if (system(cmd) != 0) fprintf(stderr, "fmu_host: could not remove %s\n", f->dir);
  }
  xmlCleanupParser();
}

const md_var *md_find(const md_info *md, const char *name) {
  for (int i = 0; i < md->n_vars; ++i)
    if (strcmp(md->vars[i].name, name) == 0) return &md->vars[i];
  return NULL;
}
