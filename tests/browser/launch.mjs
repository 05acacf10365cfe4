// Debian's chromium, headless, for the replay tests and the screenshot scripts (one place for its
// flags). A browser's first start on a fresh machine builds its font cache and profile and can take
// far longer than puppeteer's 30 s default while the rest of the suite shares the cores, so the
// start may take up to LAUNCH_TIMEOUT_MS and is tried again once, that time with chromium's own
// output shown, so that a browser that cannot start says why.
import path from 'node:path';

export const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';
const LAUNCH_TIMEOUT_MS = 180000;
const LAUNCH_ARGS = [
  '--headless',
  '--no-sandbox',
  '--disable-gpu',
  '--disable-dev-shm-usage',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
];

export async function launchChromium(puppeteer, profileDir) {
  const options = (attempt) => ({
    executablePath: CHROMIUM,
    headless: true,
    timeout: LAUNCH_TIMEOUT_MS,
    protocolTimeout: LAUNCH_TIMEOUT_MS,
    dumpio: attempt > 0,
    args: [...LAUNCH_ARGS, `--user-data-dir=${path.join(profileDir, `profile-${attempt}`)}`],
  });
  try {
    return await puppeteer.launch(options(0));
  } catch (first) {
    console.error(`chromium did not start (${first.message}); trying once more with its output shown`);
    return await puppeteer.launch(options(1));
  }
}
