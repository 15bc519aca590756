// A JSON channel's decoder for the Node checks (bridge_client.mjs, run_mcap.mjs): parses a message and validates it
// against Foxglove's own JSON Schema for a foxglove.* schema name (@foxglove/schemas, with ajv), else against the
// schema the channel advertised. Calls fail(message) on the first problem.
import Ajv from "ajv";
import foxgloveSchemas from "@foxglove/schemas/jsonschema.js";

const ajv = new Ajv({ strict: false });
const compiled = new Map();

export function jsonDecoder(topic, schemaName, schemaText, fail) {
  let validate = compiled.get(schemaName);
  if (!validate) {
    let schema;
    if (schemaName.startsWith("foxglove.")) {
      schema = foxgloveSchemas[schemaName.slice("foxglove.".length)];
      if (!schema) fail(`${topic}: ${schemaName} is not one of Foxglove's schemas`);
    } else {
      try {
        schema = JSON.parse(schemaText);
      } catch (e) {
        fail(`${topic}: advertised schema is not JSON: ${e.message}`);
      }
    }
    validate = ajv.compile(schema);
    compiled.set(schemaName, validate);
  }
  return (bytes) => {
    let message;
    try {
      message = JSON.parse(new TextDecoder().decode(bytes));
    } catch (e) {
      fail(`${topic}: a message is not JSON: ${e.message}`);
    }
    if (!validate(message)) fail(`${topic}: not a valid ${schemaName}: ${ajv.errorsText(validate.errors)}`);
    return message;
  };
}

// A JSON message small enough to print: long arrays and point data shortened to their sizes.
export function summary(message) {
  return JSON.parse(JSON.stringify(message, (key, value) => {
    if (Array.isArray(value) && value.length > 8) return { length: value.length };
    if (key === "data" && typeof value === "string") return { base64_chars: value.length };
    return value;
  }));
}
