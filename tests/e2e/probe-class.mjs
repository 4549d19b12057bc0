import { startSession, openRobotPage } from './harness.mjs';
const s = await startSession();
try {
  const { page, problems } = await openRobotPage(s, 'robot.html');
  await page.click('#generate');
  await page.waitForTimeout(500);
  for (const pl of ['dwa', 'improved-dwa', 'safe-dual-dwa']) {
    await page.selectOption('#planner', pl);
    await page.waitForTimeout(300);
    await page.selectOption('#speed', '8');
    await page.click('#play');
    await page.waitForFunction(() => document.body.dataset.outcome && document.body.dataset.outcome !== 'running', null, { timeout: 150_000 });
    const m = await page.evaluate(() => window.planlabRobot.metrics());
    console.log(pl, m.outcome, m.path_length_m, await page.$eval('#status', (e) => e.textContent));
    await page.click('#reset');
  }
  console.log(problems);
} finally { await s.close(); }
