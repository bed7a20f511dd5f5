// Validates a .glb with the Khronos glTF validator; prints the report's counts and every
// error, and exits 1 when there is an error. Usage: node validate_gltf.js MODULE_DIR FILE
const path = require('path');
const fs = require('fs');
const validator = require(path.resolve(process.argv[2], 'gltf-validator'));
const bytes = new Uint8Array(fs.readFileSync(process.argv[3]));
validator.validateBytes(bytes).then((report) => {
  const issues = report.issues;
  console.log(`errors ${issues.numErrors} warnings ${issues.numWarnings}`);
  for (const message of issues.messages) {
    if (message.severity === 0) console.log(`${message.code} ${message.pointer || ''} ${message.message}`);
  }
  process.exit(issues.numErrors === 0 ? 0 : 1);
}).catch((error) => {
  console.log(`validator failed: ${error}`);
  process.exit(2);
});
