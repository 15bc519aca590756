// Builds the bridge's web view: `node build.mjs OUTDIR` bundles src/main.js (three.js included, tree-shaken) into
// OUTDIR/app.js and copies the static files beside it. Offline: everything comes from node_modules (npm ci first).
import { copyFile, mkdir } from 'node:fs/promises';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const STATIC_FILES = ['index.html', 'style.css'];

function fail(message) {
  console.error(`build.mjs: ${String(message).split('\n')[0]}`);
  process.exit(1);
}

async function main() {
  const outArg = process.argv[2];
  if (!outArg) fail('usage: node build.mjs OUTDIR');
  const outDir = resolve(outArg);
  let esbuild;
  try {
    esbuild = await import('esbuild');
  } catch {
    fail(`esbuild not found: run 'npm ci' in ${here}`);
  }
  await mkdir(outDir, { recursive: true });
  try {
    await esbuild.build({
      entryPoints: [join(here, 'src', 'main.js')],
      outfile: join(outDir, 'app.js'),
      absWorkingDir: here,
      bundle: true,
      minify: true,
      format: 'esm',
      target: 'es2020',
      sourcemap: false,
      logLevel: 'silent',
    });
  } catch (err) {
    const first = err.errors?.[0];
    fail(first ? `${first.location?.file ?? ''}:${first.location?.line ?? ''}: ${first.text}` : err.message ?? err);
  }
  for (const name of STATIC_FILES) {
    try {
      await copyFile(join(here, name), join(outDir, name));
    } catch (err) {
      fail(`cannot copy ${name}: ${err.message}`);
    }
  }
}

main().catch((err) => fail(err?.message ?? err));
