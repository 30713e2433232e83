// Writes every file run_scene returns for each scene into OUT, as `mechdraw run` would (V8 in Node,
// the browser's engine): node web/files.js target/web OUT templates/*.toml; then diff -r with the CLI's.
const fs = require("fs"), vm = require("vm"), path = require("path");
const dir = process.argv[2], out = process.argv[3];
globalThis.self = globalThis;
vm.runInThisContext(fs.readFileSync(dir + "/mechdraw.js", "utf8"));
(async () => {
  await wasm_bindgen({ module_or_path: fs.readFileSync(dir + "/mechdraw_bg.wasm") });
  for (const f of process.argv.slice(4)) {
    let files;
    try { files = wasm_bindgen.run_scene(fs.readFileSync(f, "utf8"), f, true); }
    catch (e) { console.log(f, "ERROR", e); continue; }
    for (let i = 0; i < files.count(); i++) {
      const p = path.join(out, files.name(i));
      fs.mkdirSync(path.dirname(p), { recursive: true });
      fs.writeFileSync(p, files.bytes(i));
    }
    console.log(f, files.count(), "files");
    files.free();
  }
})();
