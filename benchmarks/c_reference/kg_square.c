/* Hand-written C99 reference of chainchaos's engines on the disordered square Klein-Gordon lattice.
 *
 *   H = sum_n [ p_n^2/2 + eps_n u_n^2/2 + u_n^4/4 ] + sum over bonds K2_b (u_a - u_c)^2 / 2,
 *
 * on nx x ny sites, site (i, j) at j nx + i, with a wall (a site at rest) beyond every edge: what
 * chainchaos.engine.lattice.advance_lattice does, one trajectory, loop by loop (the scheme's
 * tables, the tangent map, the deviation vector renormalised every check_every steps and at the
 * end, as kg_chain.c). Each site's force is the sum of its bonds' forces in the engine's order:
 * its left bond, its right bond, the bond below, the bond above, f = K2 (u_a - u_c) from a to c.
 *
 *   kick(c):  p_n += c (F_n - u_n (eps_n + u_n^2)),  dp_n += c (G_n - (eps_n + 3 u_n^2) dq_n)
 *   drift(c): u_n += c p_n,  dq_n += c dp_n   (masses 1)
 *
 * Build: gcc -O3 -march=native -std=c99 -fno-math-errno -o kg_square kg_square.c -lm
 * Run:   kg_square INPUT   with INPUT lines "key v1 v2 ..." (written by benchmarks/kg_kernel.py):
 *        nx, ny, steps, tangent (0/1), check_every, repeats, dt, stages s, kicks (s+1 values),
 *        drifts (s values), KX (ny (nx+1) values: the bond left of (i, j) at j (nx+1) + i, i = nx
 *        right of the line's last site), KY ((ny+1) nx values: the bond below (i, j) at j nx + i,
 *        j = ny above the last line), eps, q, p, dq, dp (nx ny values).
 * Output: "ns_per_step X" (best of the repeats, each from the input state), "bad_step", "log_growth",
 *        and the final q, p, dq, dp ("key v1 ... vN", %.17g).
 */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int nx, ny, N, S;  /* S = nx + 2: the stride of the padded grids */
/* Every per-site array is a grid of (nx + 2) x (ny + 2) with a border of zeros (the walls): site
 * (i, j) at (j + 1) S + i + 1, so that the loops need no test at the edges and gcc vectorises
 * them. The border of q and dq stays zero: its p and dp are zero and never kicked. */
static double *KX, *KY, *eps, *q0, *p0, *dq0, *dp0, *q, *p, *dq, *dp, *F, *G;

/* F (and G): every site's force from its four bonds, summed in the engine's order. */
static void forces(int tangent)
{
    const double *restrict U = q, *restrict DU = dq;
    double *restrict FF = F, *restrict GG = G;
    for (int j = 0; j < ny; j++) {
        const double *restrict kx = KX + j * (nx + 1), *restrict kb = KY + j * nx, *restrict ka = KY + (j + 1) * nx;
        int row = (j + 1) * S + 1;
        for (int i = 0; i < nx; i++) {
            int m = row + i;
            double u = U[m];
            FF[m] = (((U[m - 1] - u) * kx[i] - (u - U[m + 1]) * kx[i + 1]) + (U[m - S] - u) * kb[i])
                    - (u - U[m + S]) * ka[i];
        }
        if (tangent)
            for (int i = 0; i < nx; i++) {
                int m = row + i;
                double d = DU[m];
                GG[m] = ((kx[i] * (DU[m - 1] - d) - kx[i + 1] * (d - DU[m + 1])) + kb[i] * (DU[m - S] - d))
                        - ka[i] * (d - DU[m + S]);
            }
    }
}

static void kick(double c, int tangent)
{
    double *restrict P = p, *restrict DP = dp;
    const double *restrict U = q, *restrict DU = dq, *restrict E = eps, *restrict FF = F, *restrict GG = G;
    for (int j = 0; j < ny; j++) {
        int row = (j + 1) * S + 1;
        for (int i = 0; i < nx; i++) {
            int m = row + i;
            double u = U[m];
            P[m] = P[m] + c * (FF[m] - u * (E[m] + u * u));
        }
        if (tangent)
            for (int i = 0; i < nx; i++) {
                int m = row + i;
                double u = U[m];
                DP[m] = DP[m] + c * (GG[m] - (E[m] + 3.0 * (u * u)) * DU[m]);
            }
    }
}

static void drift(double c, int tangent)
{
    double *restrict U = q, *restrict DU = dq;
    const double *restrict P = p, *restrict DP = dp;
    for (int m = 0; m < S * (ny + 2); m++)
        U[m] += c * P[m];
    if (tangent)
        for (int m = 0; m < S * (ny + 2); m++)
            DU[m] += c * DP[m];
}

/* The site numbers n = j nx + i in the padded grids. */
static inline int cell(int n)
{
    return (n / nx + 1) * S + n % nx + 1;
}

static double renormalise(void)
{
    double s = 0.0;
    for (int n = 0; n < N; n++)
        s += dq[cell(n)] * dq[cell(n)] + dp[cell(n)] * dp[cell(n)];
    double norm = sqrt(s);
    for (int n = 0; n < N; n++) {
        dq[cell(n)] /= norm;
        dp[cell(n)] /= norm;
    }
    return log(norm);
}

/* Integrate n_steps; returns -1, or the number of steps done when the state became non-finite. */
static long integrate(long n_steps, int tangent, long check_every, double dt, int stages, const double *kicks,
                      const double *drifts, double *log_growth)
{
    for (long step = 0; step < n_steps; step++) {
        for (int i = 0; i <= stages; i++) {
            if (i > 0)
                drift(drifts[i - 1] * dt, tangent);
            if (kicks[i] != 0.0) {
                forces(tangent);
                kick(kicks[i] * dt, tangent);
            }
        }
        if ((step + 1) % check_every == 0 || step + 1 == n_steps) {
            double s = 0.0;
            for (int n = 0; n < N; n++)
                s += q[cell(n)] + p[cell(n)];
            if (tangent) {
                *log_growth += renormalise();
                s += dq[cell(0)];
            }
            if (!isfinite(s))
                return step + 1;
        }
    }
    return -1;
}

static void read_values(FILE *in, const char *key, double *dst, int count)
{
    for (int i = 0; i < count; i++)
        if (fscanf(in, "%lf", &dst[i]) != 1) {
            fprintf(stderr, "kg_square: %s needs %d values\n", key, count);
            exit(2);
        }
}

/* N values of a per-site array, into the interior of its padded grid. */
static void read_sites(FILE *in, const char *key, double *grid)
{
    for (int n = 0; n < N; n++)
        read_values(in, key, &grid[cell(n)], 1);
}

static void print_state(const char *key, const double *v)
{
    printf("%s", key);
    for (int n = 0; n < N; n++)
        printf(" %.17g", v[cell(n)]);
    printf("\n");
}

static double *zeros(size_t n)
{
    double *v = calloc(n, sizeof(double));
    if (!v) {
        fprintf(stderr, "kg_square: out of memory\n");
        exit(2);
    }
    return v;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s INPUT\n", argv[0]);
        return 2;
    }
    FILE *in = fopen(argv[1], "r");
    if (!in) {
        perror(argv[1]);
        return 2;
    }
    int tangent = 1, stages = 0;
    long n_steps = 0, check_every = 1000, repeats = 1;
    double dt = 0.0, kicks[32], drifts[32];
    char key[64];
    while (fscanf(in, "%63s", key) == 1) {
        if (!strcmp(key, "nx")) { if (fscanf(in, "%d", &nx) != 1 || nx < 1) return 2; }
        else if (!strcmp(key, "ny")) {
            if (fscanf(in, "%d", &ny) != 1 || ny < 1 || nx < 1) return 2;
            N = nx * ny, S = nx + 2;
            size_t cells = (size_t)S * (ny + 2);
            KX = zeros((size_t)ny * (nx + 1)), KY = zeros((size_t)(ny + 1) * nx);
            eps = zeros(cells), F = zeros(cells), G = zeros(cells);
            q0 = zeros(cells), p0 = zeros(cells), dq0 = zeros(cells), dp0 = zeros(cells);
            q = zeros(cells), p = zeros(cells), dq = zeros(cells), dp = zeros(cells);
        }
        else if (!strcmp(key, "steps")) { if (fscanf(in, "%ld", &n_steps) != 1) return 2; }
        else if (!strcmp(key, "tangent")) { if (fscanf(in, "%d", &tangent) != 1) return 2; }
        else if (!strcmp(key, "check_every")) { if (fscanf(in, "%ld", &check_every) != 1) return 2; }
        else if (!strcmp(key, "repeats")) { if (fscanf(in, "%ld", &repeats) != 1) return 2; }
        else if (!strcmp(key, "stages")) { if (fscanf(in, "%d", &stages) != 1 || stages < 1 || stages > 30) return 2; }
        else if (!strcmp(key, "dt")) read_values(in, key, &dt, 1);
        else if (!strcmp(key, "kicks")) read_values(in, key, kicks, stages + 1);
        else if (!strcmp(key, "drifts")) read_values(in, key, drifts, stages);
        else if (!N) { fprintf(stderr, "kg_square: nx and ny must come before %s\n", key); return 2; }
        else if (!strcmp(key, "KX")) read_values(in, key, KX, ny * (nx + 1));
        else if (!strcmp(key, "KY")) read_values(in, key, KY, (ny + 1) * nx);
        else if (!strcmp(key, "eps")) read_sites(in, key, eps);
        else if (!strcmp(key, "q")) read_sites(in, key, q0);
        else if (!strcmp(key, "p")) read_sites(in, key, p0);
        else if (!strcmp(key, "dq")) read_sites(in, key, dq0);
        else if (!strcmp(key, "dp")) read_sites(in, key, dp0);
        else { fprintf(stderr, "kg_square: unknown key %s\n", key); return 2; }
    }
    fclose(in);
    if (!N || n_steps < 1 || check_every < 1 || repeats < 1 || !(dt > 0.0) || !stages) {
        fprintf(stderr, "kg_square: need nx, ny, stages, steps >= 1, check_every >= 1, dt > 0\n");
        return 2;
    }

    size_t bytes = (size_t)S * (ny + 2) * sizeof(double);
    double best = INFINITY, log_growth = 0.0;
    long bad = -1;
    for (long r = 0; r < repeats; r++) {
        memcpy(q, q0, bytes);
        memcpy(p, p0, bytes);
        memcpy(dq, dq0, bytes);
        memcpy(dp, dp0, bytes);
        log_growth = 0.0;
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        bad = integrate(n_steps, tangent, check_every, dt, stages, kicks, drifts, &log_growth);
        clock_gettime(CLOCK_MONOTONIC, &t1);
        double ns = 1e9 * (double)(t1.tv_sec - t0.tv_sec) + (double)(t1.tv_nsec - t0.tv_nsec);
        if (ns < best)
            best = ns;
    }
    printf("ns_per_step %.6g\n", best / (double)n_steps);
    printf("bad_step %ld\n", bad);
    printf("log_growth %.17g\n", log_growth);
    print_state("q", q);
    print_state("p", p);
    print_state("dq", dq);
    print_state("dp", dp);
    return 0;
}
