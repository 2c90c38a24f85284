// Fails fast when an npm script runs on a Node older than the one the project pins (the `node` package, 24).
const major = Number(process.versions.node.split('.')[0]);
if (major < 24) {
  console.error(`taos-physics needs Node 24 (found ${process.version}). Run it through npm scripts, which use the pinned node package.`);
  process.exit(1);
}
