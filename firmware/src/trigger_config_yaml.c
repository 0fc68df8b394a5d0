// syncap-trigger --config FILE.yaml: a flat YAML file of its options, or its part of the rig file
// (docs/guide/rig.md), read with libyaml's document loader so that every entry keeps its line and
// column for the error message.
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <yaml.h>

#include "trigger_options.h"

// The sections of a rig file; a file with any of them at the top is one.
static const char* const rig_sections[] = {"trigger", "host", "edges", "cameras"};

struct yaml_reading {
  const char* path;
  yaml_document_t* document;
  struct trigger_options* options;
  char* error;
  size_t size;
};

// "PATH:LINE:COLUMN: key 'KEY': WHAT" in the error, at node; false.
static bool fail_at(const struct yaml_reading* r, const yaml_node_t* node, const char* key,
                    const char* what) {
  snprintf(r->error, r->size, "%s:%zu:%zu: key '%s': %s", r->path, node->start_mark.line + 1,
           node->start_mark.column + 1, key, what);
  return false;
}

static const char* scalar_text(const yaml_node_t* node) {
  return node->type == YAML_SCALAR_NODE ? (const char*)node->data.scalar.value : NULL;
}

static bool is_rig_section(const char* key) {
  for (size_t i = 0; i < sizeof(rig_sections) / sizeof(rig_sections[0]); ++i) {
    if (strcmp(key, rig_sections[i]) == 0) return true;
  }
  return false;
}

// A scalar as it is, a list of scalars joined by commas (lines: [17, 27] is "17,27"); NULL with the
// error set for anything else.
static const char* value_text(const struct yaml_reading* r, const char* key,
                              const yaml_node_t* value) {
  if (value->type == YAML_SCALAR_NODE) {
    if (value->data.scalar.length == 0) {
      fail_at(r, value, key, "missing value");
      return NULL;
    }
    return trigger_options_keep(r->options, (const char*)value->data.scalar.value,
                                value->data.scalar.length);
  }
  if (value->type != YAML_SEQUENCE_NODE) {
    fail_at(r, value, key, "is not a single value or a list");
    return NULL;
  }
  char joined[512] = "";
  size_t length = 0;
  for (yaml_node_item_t* item = value->data.sequence.items.start;
       item < value->data.sequence.items.top; ++item) {
    const char* text = scalar_text(yaml_document_get_node(r->document, *item));
    if (text == NULL) {
      fail_at(r, value, key, "a list holds something other than single values");
      return NULL;
    }
    const int n =
        snprintf(joined + length, sizeof(joined) - length, "%s%s", length > 0 ? "," : "", text);
    if (n < 0 || (size_t)n >= sizeof(joined) - length) {
      fail_at(r, value, key, "list too long");
      return NULL;
    }
    length += (size_t)n;
  }
  return trigger_options_keep(r->options, joined, length);
}

static bool apply_entry(const struct yaml_reading* r, const char* key, const yaml_node_t* value) {
  const char* text = value_text(r, key, value);
  if (text == NULL) return false;
  const char* why = trigger_options_apply_key(key, text, r->options);
  if (why == NULL) return true;
  char detail[400];
  snprintf(detail, sizeof(detail), "'%s' %s", text, why);
  return fail_at(r, value, key, detail);
}

// Every entry of a mapping that must hold only options (a flat file, the trigger: section).
static bool apply_all(const struct yaml_reading* r, const yaml_node_t* mapping) {
  for (yaml_node_pair_t* pair = mapping->data.mapping.pairs.start;
       pair < mapping->data.mapping.pairs.top; ++pair) {
    const yaml_node_t* key_node = yaml_document_get_node(r->document, pair->key);
    const char* key = scalar_text(key_node);
    if (key == NULL) return fail_at(r, key_node, "?", "a key must be a name");
    if (!trigger_options_is_key(key)) {
      return fail_at(r, key_node, key, "not an option of syncap-trigger");
    }
    if (!apply_entry(r, key, yaml_document_get_node(r->document, pair->value))) return false;
  }
  return true;
}

static bool is_rig(const yaml_document_t* document, const yaml_node_t* root) {
  for (yaml_node_pair_t* pair = root->data.mapping.pairs.start; pair < root->data.mapping.pairs.top;
       ++pair) {
    const char* key = scalar_text(yaml_document_get_node((yaml_document_t*)document, pair->key));
    if (key != NULL && is_rig_section(key)) return true;
  }
  return false;
}

// The rig file: the shared top-level entries that are trigger options, then the trigger: section.
static bool apply_rig(const struct yaml_reading* r, const yaml_node_t* root) {
  const yaml_node_t* section = NULL;
  for (yaml_node_pair_t* pair = root->data.mapping.pairs.start; pair < root->data.mapping.pairs.top;
       ++pair) {
    const char* key = scalar_text(yaml_document_get_node(r->document, pair->key));
    const yaml_node_t* value = yaml_document_get_node(r->document, pair->value);
    if (key == NULL) continue;
    if (strcmp(key, "trigger") == 0) {
      section = value;
    } else if (!is_rig_section(key) && trigger_options_is_key(key) && !apply_entry(r, key, value)) {
      return false;
    }
  }
  if (section == NULL) return true;
  if (section->type != YAML_MAPPING_NODE) {
    return fail_at(r, section, "trigger", "must be a section of 'key: value' entries");
  }
  return apply_all(r, section);
}

static bool apply_document(const struct yaml_reading* r) {
  const yaml_node_t* root = yaml_document_get_root_node(r->document);
  if (root == NULL) return true;  // an empty file sets nothing
  if (root->type != YAML_MAPPING_NODE) {
    snprintf(r->error, r->size, "%s:%zu:%zu: expected 'key: value' entries", r->path,
             root->start_mark.line + 1, root->start_mark.column + 1);
    return false;
  }
  return is_rig(r->document, root) ? apply_rig(r, root) : apply_all(r, root);
}

bool trigger_options_load_yaml(const char* path, struct trigger_options* options, char* error,
                               size_t size) {
  FILE* file = fopen(path, "rb");
  if (file == NULL) {
    snprintf(error, size, "%s: cannot read: %s", path, strerror(errno));
    return false;
  }
  yaml_parser_t parser;
  yaml_document_t document;
  yaml_parser_initialize(&parser);
  yaml_parser_set_input_file(&parser, file);
  bool ok = yaml_parser_load(&parser, &document) != 0;
  if (!ok) {
    snprintf(error, size, "%s:%zu:%zu: not YAML: %s", path, parser.problem_mark.line + 1,
             parser.problem_mark.column + 1, parser.problem != NULL ? parser.problem : "?");
  } else {
    const struct yaml_reading reading = {path, &document, options, error, size};
    ok = apply_document(&reading);
    yaml_document_delete(&document);
  }
  yaml_parser_delete(&parser);
  fclose(file);
  return ok;
}
