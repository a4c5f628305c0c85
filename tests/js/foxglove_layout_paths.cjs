// The message paths of a Foxglove layout (docs/foxglove-layout.json) and their resolution in a
// channel's ros2msg schema, so that the tier can tell that the layout's fields exist on the live
// station (firmware/hubctl/test/foxglove_layout_test.cc checks every path against the station's
// types in the default suite). Layout files: { configById: {"<Panel>!<id>": config}, layout: the
// panels' mosaic tree, ... }; Plot and StateTransitions configs have paths[].value, RawMessages a
// topicPath, the diagnostics panels a topicToRender.
"use strict";

// "/tool_ecu/lift/state.position_mm" -> {topic, fields: ["position_mm"]}; topics have no '.'.
function splitPath(text) {
  const dot = text.indexOf(".");
  const topic = dot < 0 ? text : text.slice(0, dot);
  const fields = dot < 0 ? [] : text.slice(dot + 1).split(".");
  if (!topic.startsWith("/") || fields.some((f) => !/^[A-Za-z_][A-Za-z0-9_]*$/.test(f)))
    throw new Error(`'${text}': only /topic.field.field paths are used in this layout`);
  return { text, topic, fields };
}

function layoutPaths(layout) {
  const out = [];
  for (const [panel, config] of Object.entries(layout.configById ?? {})) {
    const type = panel.split("!")[0];
    if (type === "Plot" || type === "StateTransitions") {
      for (const p of config.paths ?? []) out.push({ panel, ...splitPath(p.value) });
    } else if (type === "RawMessages") {
      out.push({ panel, ...splitPath(config.topicPath) });
    } else if (type === "DiagnosticSummary" || type === "DiagnosticStatusPanel") {
      out.push({ panel, ...splitPath(config.topicToRender) });
    }
  }
  return out;
}

// Undefined when `fields` name a field of the root type (through nested types), else why not.
function resolvePath(definitions, fields) {
  const byName = new Map(definitions.filter((d) => d.name).map((d) => [d.name, d]));
  let current = definitions[0];
  for (const [i, name] of fields.entries()) {
    const field = current.definitions.find((f) => !f.isConstant && f.name === name);
    if (!field) return `no field '${name}'`;
    if (i === fields.length - 1) return undefined;
    if (!field.isComplex || field.isArray) return `'${name}' has no fields`;
    current = byName.get(field.type);
    if (!current) return `no definition of ${field.type}`;
  }
  return undefined;
}

module.exports = { layoutPaths, resolvePath, splitPath };
