// A decoded ROS 2 message (from @foxglove/rosmsg2-serialization) against the JSON `hubctl echo
// --json` printed, field by field as the message definition types them: float32 compared as
// float32 (echo prints the shortest decimal that reads back as the same float: 0.8, where the
// decoder gives 0.800000011920929), 64-bit integers as BigInt against JSON numbers, times as
// {sec, nanosec}, non-finite floats as echo's null. Returns the differences (empty: equal).
"use strict";

const INTEGER = new Set(["int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64", "byte", "char"]);

function sameScalar(type, decoded, echoed) {
  if (type === "bool") return decoded === echoed;
  if (type === "string" || type === "wstring") return decoded === echoed;
  if (INTEGER.has(type)) return typeof echoed === "number" && Number(decoded) === echoed;
  if (type === "float32" || type === "float64") {
    if (!Number.isFinite(decoded)) return echoed === null;
    if (typeof echoed !== "number") return false;
    return type === "float32" ? Math.fround(decoded) === Math.fround(echoed) : decoded === echoed;
  }
  return false;
}

function compareField(field, decoded, echoed, byName, path, problems) {
  if (field.isArray) {
    if (!Array.isArray(echoed)) return problems.push(`${path}: echo has ${JSON.stringify(echoed)}, not an array`);
    const items = Array.from(decoded ?? []);
    if (items.length !== echoed.length) return problems.push(`${path}: ${items.length} elements in the file, ${echoed.length} echoed`);
    items.forEach((item, i) => compareOne(field, item, echoed[i], byName, `${path}[${i}]`, problems));
    return undefined;
  }
  return compareOne(field, decoded, echoed, byName, path, problems);
}

function compareOne(field, decoded, echoed, byName, path, problems) {
  if (field.type === "time" || field.type === "duration") {
    if (echoed === null || typeof echoed !== "object" || Number(decoded?.sec) !== echoed.sec || Number(decoded?.nanosec) !== echoed.nanosec)
      problems.push(`${path}: ${JSON.stringify(decoded)} in the file, ${JSON.stringify(echoed)} echoed`);
    return;
  }
  if (field.isComplex) {
    compareStruct(byName.get(field.type), decoded, echoed, byName, path, problems);
    return;
  }
  if (!sameScalar(field.type, decoded, echoed)) {
    const shown = typeof decoded === "bigint" ? `${decoded}n` : JSON.stringify(decoded);
    problems.push(`${path} (${field.type}): ${shown} in the file, ${JSON.stringify(echoed)} echoed`);
  }
}

function compareStruct(definition, decoded, echoed, byName, path, problems) {
  if (!definition) return problems.push(`${path}: no definition in the schema`);
  if (echoed === null || typeof echoed !== "object") return problems.push(`${path}: echo has ${JSON.stringify(echoed)}`);
  const fields = definition.definitions.filter((f) => !f.isConstant);
  for (const field of fields) {
    const where = path ? `${path}.${field.name}` : field.name;
    if (!(field.name in echoed)) problems.push(`${where}: in the file, not echoed`);
    else compareField(field, decoded?.[field.name], echoed[field.name], byName, where, problems);
  }
  for (const key of Object.keys(echoed)) {
    if (!fields.some((f) => f.name === key)) problems.push(`${path ? `${path}.` : ""}${key}: echoed, not in the schema`);
  }
  return undefined;
}

// `definitions`: @foxglove/rosmsg's parse() of the channel's schema; the first is the root type.
function compareTyped(decoded, echoed, definitions) {
  const byName = new Map(definitions.filter((d) => d.name).map((d) => [d.name, d]));
  const problems = [];
  compareStruct(definitions[0], decoded, echoed, byName, "", problems);
  return problems;
}

module.exports = { compareTyped };
