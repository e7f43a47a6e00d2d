// The port the e2e specs serve the built app on: 4173 (CI) unless
// VM_E2E_PORT is set, so parallel checkouts on one machine do not share (or
// reuse) one another's server.
export const PORT = Number(process.env.VM_E2E_PORT || 4173);
export const HOST = `127.0.0.1:${PORT}`;
