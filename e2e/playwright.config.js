// Playwright runs the built app (web/dist of this checkout, served by vite
// preview on VM_E2E_PORT, default 4173) in Debian's Chromium: browsers cannot
// be downloaded here.
import { defineConfig } from '@playwright/test';

import { HOST, PORT } from './port.js';

export default defineConfig({
  testDir: '.',
  timeout: 90_000,
  expect: { timeout: 30_000 },
  workers: 1,
  retries: 0,
  reporter: [['list']],
  use: {
    baseURL: `http://${HOST}/`,
    acceptDownloads: true,
    launchOptions: {
      executablePath: process.env.CHROMIUM_PATH || '/usr/bin/chromium',
      args: [
        '--no-sandbox',
        '--disable-gpu',
        '--disable-background-networking',
        '--disable-component-update',
        '--no-first-run',
        '--disable-sync',
        '--disable-quic',
      ],
    },
  },
  webServer: {
    command: `npx vite preview --config web/vite.config.js --host 127.0.0.1 --port ${PORT} --strictPort`,
    cwd: '..',
    url: `http://${HOST}/`,
    reuseExistingServer: !process.env.CI,
    timeout: 60_000,
  },
});
