// Stub for msgpackr's optional native accelerator: exports nothing, so msgpackr keeps its pure-JS string decoding.
module.exports = null;
