# The taos-physics server image: `serve` on port 7777 on every interface, with the built browser client. Runs as a
# single process, in a Redis fleet (--redis, TAOS_REDIS_URL) or as an Agones GameServer (found from the sidecar's
# environment). docs/deploy.md says how; deploy/agones/ holds the manifests.
FROM node:24-bookworm-slim AS build
WORKDIR /app
# Install scripts are skipped: the pinned `node` package would fetch a second Node (the image has Node 24), and the
# packages that have scripts work without them (esbuild's binary comes in its platform package).
COPY package.json package-lock.json ./
COPY scripts/stubs ./scripts/stubs
RUN npm ci --omit=dev --ignore-scripts --no-audit --no-fund
COPY . .
# Plain `node`, not `npm run`: npm would put the skipped `node` package's placeholder first on the PATH.
RUN node scripts/build-client.ts

FROM node:24-bookworm-slim
ENV NODE_ENV=production
WORKDIR /app
COPY --from=build --chown=node:node /app /app
USER node
EXPOSE 7777
HEALTHCHECK --interval=10s --timeout=3s CMD ["node", "-e", "fetch('http://127.0.0.1:7777/healthz').then((r) => process.exit(r.ok ? 0 : 1), () => process.exit(1))"]
ENTRYPOINT ["node", "bin/taos-physics.js", "serve", "--host", "0.0.0.0", "--port", "7777"]
