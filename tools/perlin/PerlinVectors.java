/*
 * PerlinVectors.java - writes tests/vectors/noise_perlin.csv from Ken
 * Perlin's improved noise as his 2002 Java reference computes it
 * ("Improving Noise", SIGGRAPH 2002; the reference class ImprovedNoise):
 * the same permutation, the same fade curve 6t^5 - 15t^4 + 10t^3, the same
 * twelve-plus-four gradients picked by the low four bits of the hash, and
 * the same order of operations in Java's IEEE double. It is independent of
 * svet's C code (src/texture/noise.c), which the C tests check against the
 * file. Rosetta Code's Perlin-noise task quotes the reference's value at
 * (3.14, 42, 7): 0.13691995878400012; this program refuses to write the
 * file unless it reproduces it exactly.
 * Run: javac -d /tmp tools/perlin/PerlinVectors.java &&
 *      java -cp /tmp PerlinVectors > tests/vectors/noise_perlin.csv
 * (`make noise-vectors` does both when a JDK is installed.)
 */
public final class PerlinVectors {
    static final int[] PERMUTATION = {
        151,160,137,91,90,15,131,13,201,95,96,53,194,233,7,225,140,36,103,30,69,142,
        8,99,37,240,21,10,23,190,6,148,247,120,234,75,0,26,197,62,94,252,219,203,117,
        35,11,32,57,177,33,88,237,149,56,87,174,20,125,136,171,168,68,175,74,165,71,
        134,139,48,27,166,77,146,158,231,83,111,229,122,60,211,133,230,220,105,92,41,
        55,46,245,40,244,102,143,54,65,25,63,161,1,216,80,73,209,76,132,187,208,89,
        18,169,200,196,135,130,116,188,159,86,164,100,109,198,173,186,3,64,52,217,226,
        250,124,123,5,202,38,147,118,126,255,82,85,212,207,206,59,227,47,16,58,17,182,
        189,28,42,223,183,170,213,119,248,152,2,44,154,163,70,221,153,101,155,167,43,
        172,9,129,22,39,253,19,98,108,110,79,113,224,232,178,185,112,104,218,246,97,
        228,251,34,242,193,238,210,144,12,191,179,162,241,81,51,145,235,249,14,239,
        107,49,192,214,31,181,199,106,157,184,84,204,176,115,121,50,45,127,4,150,254,
        138,236,205,93,222,114,67,29,24,72,243,141,128,195,78,66,215,61,156,180
    };
    static final int[] P = new int[512];
    static {
        for (int i = 0; i < 256; i++)
            P[i] = P[256 + i] = PERMUTATION[i];
    }

    static double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
    static double lerp(double t, double a, double b) { return a + t * (b - a); }

    /* the dot product of (x, y, z) with one of the gradients
     * (1,1,0), (-1,1,0), ... (0,-1,-1), the last four repeating four of them */
    static double grad(int hash, double x, double y, double z) {
        int h = hash & 15;
        double u = h < 8 ? x : y;
        double v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
        return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
    }

    static double noise(double x, double y, double z) {
        int X = (int) Math.floor(x) & 255, Y = (int) Math.floor(y) & 255,
            Z = (int) Math.floor(z) & 255;
        x -= Math.floor(x);
        y -= Math.floor(y);
        z -= Math.floor(z);
        double u = fade(x), v = fade(y), w = fade(z);
        int A = P[X] + Y, AA = P[A] + Z, AB = P[A + 1] + Z;
        int B = P[X + 1] + Y, BA = P[B] + Z, BB = P[B + 1] + Z;
        double x00 = lerp(u, grad(P[AA], x, y, z), grad(P[BA], x - 1, y, z));
        double x10 = lerp(u, grad(P[AB], x, y - 1, z), grad(P[BB], x - 1, y - 1, z));
        double x01 = lerp(u, grad(P[AA + 1], x, y, z - 1), grad(P[BA + 1], x - 1, y, z - 1));
        double x11 = lerp(u, grad(P[AB + 1], x, y - 1, z - 1), grad(P[BB + 1], x - 1, y - 1, z - 1));
        return lerp(w, lerp(v, x00, x10), lerp(v, x01, x11));
    }

    /* the points: a 64-bit LCG (Knuth's MMIX constants) so that the list is
     * the same on every JVM; each input is rounded to a float first, so that
     * a float and a double port start from the same exact inputs */
    static long state = 0x5eed5eedL;
    static double next(double lo, double hi) {
        state = state * 6364136223846793005L + 1442695040888963407L;
        double u = (double) (state >>> 11) / (double) (1L << 53);
        return (float) (lo + (hi - lo) * u);
    }

    static void row(String kind, double x, double y, double z) {
        System.out.println(kind + "," + fmt(x) + "," + fmt(y) + "," + fmt(z) + ","
                           + fmt(noise(x, y, z)));
    }
    static String fmt(double d) { return String.format(java.util.Locale.ROOT, "%.17g", d); }

    public static void main(String[] args) {
        if (noise(3.14, 42, 7) != 0.13691995878400012) {
            System.err.println("PerlinVectors: noise(3.14, 42, 7) = " + noise(3.14, 42, 7)
                               + ", not the reference's 0.13691995878400012");
            System.exit(1);
        }
        System.out.println("# Perlin's improved noise (Perlin 2002) at points, from his Java reference's");
        System.out.println("# algorithm run in Java double (tools/perlin/PerlinVectors.java). Inputs are");
        System.out.println("# floats printed exactly; 'rosetta' is Rosetta Code's quoted point (3.14 is");
        System.out.println("# the double nearest 3.14 there, not a float: a float port reads 3.14f).");
        System.out.println("# Tolerances: double 1e-12; float 4e-6 (x - floor(x) is exact for a float,");
        System.out.println("# then about 30 roundings of terms below 2 in magnitude, 2^-24 each).");
        System.out.println("kind,x,y,z,noise");
        System.out.println("rosetta,3.1400000000000001,42.000000000000000,7.0000000000000000,"
                           + fmt(noise(3.14, 42, 7)));
        for (int i = -2; i <= 2; i++)
            row("lattice", i, 2 * i + 1, 3 - i);
        for (int i = 0; i < 120; i++)
            row("unit", next(-4, 4), next(-4, 4), next(-4, 4));
        for (int i = 0; i < 40; i++)
            row("wide", next(-300, 300), next(-300, 300), next(-300, 300));
        for (int i = 0; i < 20; i++) {
            double x = Math.floor(next(-10, 10));
            row("near-lattice", x + next(-1e-3, 1e-3), next(-2, 2), next(-2, 2));
        }
    }
}
