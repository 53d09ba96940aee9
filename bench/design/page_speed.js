// The designer's page's cost per input change: its WebAssembly build of `chutelab estimate` run in
// node (the browser runs the same module), one design (JSON + drawing) and the page's 25-point
// sweep against plate distance (CSV + chart). Usage: node bench/design/page_speed.js BUILD_DIR
const M = require(require('path').resolve(process.argv[2], 'app/design/wasm/chutelab_design.js'));
M().then(function (m) {
  function run(a) { const v = new m.StringList(); a.forEach(function (x) { v.push_back(x); }); const r = m.run(v); v.delete(); return r; }
  const base = ['estimate', '--setup', '/datasets/grima2010/setup.toml', '--belt-speed', '4', '--mass-flow', '35'];
  const one = base.concat(['--plate-distance', '450', '--format', 'json', '--svg', '/tmp/d.svg']);
  const sweep = base.concat(['--sweep', 'plate_distance=180:720:22.5', '--format', 'csv', '--svg', '/tmp/s.svg']);
  for (let i = 0; i < 5; i++) { run(one); run(sweep); }  // warm-up (JIT tiers)
  function time(args, n) {
    const t = process.hrtime.bigint();
    for (let i = 0; i < n; i++) if (run(args).code !== 0) throw new Error('estimate failed');
    return Number(process.hrtime.bigint() - t) / n / 1e6;
  }
  const a = time(one, 200), b = time(sweep, 50);
  console.log('wasm one design (json + svg)          ' + a.toFixed(2) + ' ms');
  console.log('wasm 25-point sweep (csv + chart)     ' + b.toFixed(2) + ' ms');
  console.log('wasm per input change on the page     ' + (a + b).toFixed(2) + ' ms');
});
