// Times the browser entry in V8 (Node): the module's compile, and run_scene per scene (3 runs).
//   node web/time.js target/web templates/fourbar-chebyshev.toml ...   (on a quiet machine)
const fs = require("fs");
const vm = require("vm");
const dir = process.argv[2];
globalThis.self = globalThis;
vm.runInThisContext(fs.readFileSync(dir + "/mechdraw.js", "utf8"));
const bytes = fs.readFileSync(dir + "/mechdraw_bg.wasm");
(async () => {
  let t = performance.now();
  await wasm_bindgen({ module_or_path: bytes });
  console.log(`init (compile + instantiate ${bytes.length} bytes): ${(performance.now() - t).toFixed(0)} ms`);
  for (const f of process.argv.slice(3)) {
    const text = fs.readFileSync(f, "utf8");
    for (const frames of [false, true]) {
      const times = [];
      let n = 0, size = 0;
      for (let k = 0; k < 3; k++) {
        t = performance.now();
        const files = wasm_bindgen.run_scene(text, f, frames);
        n = files.count(); size = 0;
        for (let i = 0; i < n; i++) size += files.bytes(i).length;
        files.free();
        times.push(performance.now() - t);
      }
      console.log(`${f} frames=${frames}: ${n} files, ${size} bytes, ms ${times.map((x) => x.toFixed(0)).join(" ")}`);
    }
  }
})().catch((e) => { console.error("ERR", e); process.exit(1); });
